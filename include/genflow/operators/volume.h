// SPDX-License-Identifier: MIT
#pragma once

#include "genflow/mesh.h"

namespace genflow {

/// Signed enclosed volume V = (1/6) Σ_f x_a·(x_b × x_c) (docs/formulas.md §1): positive for a
/// closed mesh with outward (counter-clockwise) faces, negative if its faces point inward. On a
/// mesh with boundary the value depends on the origin and is not a volume. \throws InvalidInput if
/// F indexes outside V or V holds a non-finite coordinate.
[[nodiscard]] double enclosed_volume(const TriangleMesh& mesh);

/// ∂V/∂X (#V×3): (1/6) Σ_{f∋a} x_b × x_c for each corner a of face (a, b, c). On a closed mesh
/// it equals ñ_a/3, a third of the area-weighted vertex normal.
/// \throws InvalidInput as `enclosed_volume()`.
[[nodiscard]] VertexField enclosed_volume_gradient(const TriangleMesh& mesh);

}  // namespace genflow
