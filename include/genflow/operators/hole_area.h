// SPDX-License-Identifier: MIT
#pragma once

#include "genflow/mesh.h"

namespace genflow {

/// The area of the holes in a surface, estimated from its boundary: the sum over the loops
/// around its gaps (boundary_loops(): a hole touching another or the border is a loop of its
/// own, so their areas add instead of cancelling) of the loop's vector area
/// |½ Σ_{(a→b)} (x_a − c) × (x_b − c)|, the edges oriented by their faces and c the loop's
/// centroid. That is the area of the flat patch that closes a planar loop (a hole of radius r:
/// π r²) and, for a bent one, of its shadow on the plane it faces most; a ragged edge barely
/// changes it, unlike the loop's length. 0 for a closed mesh; the same at any position and
/// rotation, times s² at scale s.
/// \throws InvalidInput if F indexes outside V or V holds a non-finite coordinate.
[[nodiscard]] double hole_area(const TriangleMesh& mesh);

}  // namespace genflow
