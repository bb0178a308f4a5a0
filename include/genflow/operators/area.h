// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

#include "genflow/mesh.h"

namespace genflow {

/// Triangle areas A_f = ½|(x_b − x_a)×(x_c − x_a)|, a #F vector.
/// \throws InvalidInput if F indexes outside V or V holds a non-finite coordinate.
[[nodiscard]] Eigen::VectorXd face_areas(const TriangleMesh& mesh);

/// Total surface area Σ_f A_f.
/// \throws InvalidInput as `face_areas()`.
[[nodiscard]] double surface_area(const TriangleMesh& mesh);

/// The L2 differential of the surface area, ∂A/∂X (#V×3): for each face (a, b, c),
/// ∂A_f/∂x_a = ½ n_f × (x_c − x_b). It equals K X with K = `cotan_stiffness()` (up to the
/// cotangent clamp), i.e. m_i·2H_i n_i: the mean-curvature normal. Zero-area faces contribute
/// nothing, as their gradient is undefined.
/// \throws InvalidInput as `face_areas()`.
[[nodiscard]] VertexField surface_area_gradient(const TriangleMesh& mesh);

}  // namespace genflow
