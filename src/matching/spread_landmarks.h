// SPDX-License-Identifier: MIT
// Landmarks spread into a dense map of a partial target, by their geodesic distances.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "genflow/matching/landmarks.h"
#include "genflow/mesh.h"

namespace genflow::detail {

/// `landmarks` and, after them, up to `count` more spread over `target` (docs/matching.md,
/// "Landmarks onto a partial target"): target vertices spread by farthest-point sampling, each
/// given the template vertex whose Gaussians of the geodesic distance to the landmarks,
/// exp(−(d_k/σ)²) with σ their spacing √(template area / K), are nearest its own. A point lies
/// about as far from each near landmark on a view as on the whole shape, and a far landmark,
/// whose path the view may have cut, weighs nothing. Landmarks on faces of both meshes are
/// assumed (every vertex index valid); with fewer than three, which leave points on a surface
/// undecided, `landmarks` alone.
[[nodiscard]] std::vector<Landmark> spread_landmarks(const TriangleMesh& template_mesh,
                                                     const TriangleMesh& target,
                                                     const std::vector<Landmark>& landmarks,
                                                     Eigen::Index count);

}  // namespace genflow::detail
