// SPDX-License-Identifier: MIT
// The one-sided Hausdorff distance from one surface to another, exact to a tolerance, by bound
// and prune on the faces of the first.
#pragma once

#include <Eigen/Core>

#include "genflow/mesh.h"
#include "genflow/spatial/closest_point.h"

namespace genflow::detail {

struct OneSidedHausdorff {
    double distance = 0;     ///< max_{p ∈ from} d(p, to), found at `farthest_point`
    double upper_bound = 0;  ///< a proven bound of the true value, ≥ distance + tolerance
    Eigen::Vector3d farthest_point = Eigen::Vector3d::Zero();
};

/// max_{p ∈ from} d(p, to) to within `tolerance` (> 0), `to_bvh` being the tree of `to`. The
/// same bits for any thread count.
[[nodiscard]] OneSidedHausdorff one_sided_hausdorff(const TriangleMesh& from,
                                                    const TriangleMesh& to,
                                                    const TriangleBvh& to_bvh, double tolerance);

}  // namespace genflow::detail
