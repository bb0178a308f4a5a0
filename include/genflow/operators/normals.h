// SPDX-License-Identifier: MIT
#pragma once

#include "genflow/mesh.h"

namespace genflow {

/// Unit face normals n_f = (x_b − x_a)×(x_c − x_a)/|…|, #F×3; they point outward for
/// counter-clockwise faces. Zero rows for zero-area faces.
/// \throws InvalidInput if F indexes outside V or V holds a non-finite coordinate.
[[nodiscard]] Eigen::MatrixX3d face_normals(const TriangleMesh& mesh);

/// Area-weighted unit vertex normals n_i = ñ_i/|ñ_i| with ñ_i = Σ_{f∋i} A_f n_f (docs/formulas.md
/// §1), #V×3. Zero rows where ñ_i vanishes (unreferenced vertices, all faces degenerate, or
/// cancelling faces). On a closed mesh, ñ_i = 3 ∂V/∂x_i.
/// \throws InvalidInput as `face_normals()`.
[[nodiscard]] Eigen::MatrixX3d vertex_normals(const TriangleMesh& mesh);

}  // namespace genflow
