// SPDX-License-Identifier: MIT
#pragma once

#include "genflow/mesh.h"

namespace genflow {

/// Length of the diagonal of the axis-aligned bounding box of the vertices (0 for no vertices).
/// Every scale-free parameter of genflow is relative to this or to `mean_edge_length()`.
/// \throws InvalidInput if V holds a non-finite coordinate.
[[nodiscard]] double bounding_box_diagonal(const TriangleMesh& mesh);

/// Mean length of the mesh's undirected edges, each counted once (0 for no faces).
/// \throws InvalidInput if F indexes outside V or V holds a non-finite coordinate.
[[nodiscard]] double mean_edge_length(const TriangleMesh& mesh);

}  // namespace genflow
