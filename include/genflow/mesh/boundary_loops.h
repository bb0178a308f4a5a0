// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include "genflow/mesh.h"

namespace genflow {

/// The loops of a surface's boundary, one around each gap in it (a hole, the open side of a
/// single view), each as the vertices its edges (oriented_boundary_edges()) run through, in
/// that order.
///
/// Where several loops meet at a vertex (a hole whose rim touches the border, two holes
/// touching at a corner) the edges at it do not say which continues which. Each edge entering
/// the vertex is continued by the edge leaving it across the same gap: the first one met
/// turning counter-clockwise about the vertex's normal from the entering edge, since a
/// boundary runs with the surface on its left. A hole touching the border then stays a loop of
/// its own, and its vector area adds to the border's instead of cancelling it (hole_area()).
/// A chain whose edges cannot be continued (faces that disagree in orientation) is returned as
/// far as it runs. None for a closed mesh.
/// \throws InvalidInput if F indexes outside V or V holds a non-finite coordinate.
[[nodiscard]] std::vector<std::vector<int>> boundary_loops(const TriangleMesh& mesh);

}  // namespace genflow
