// SPDX-License-Identifier: MIT
// Points spread over a set by farthest-point sampling.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace genflow::detail {

/// Up to `count` rows of `points` spread over them: `first`, then each time the point farthest
/// (Euclidean) from those taken. Fewer where every other point coincides with one taken.
/// Deterministic: ties go to the lowest index. `first` must be a valid row.
[[nodiscard]] std::vector<Eigen::Index> farthest_points(const Eigen::MatrixX3d& points,
                                                        Eigen::Index first, Eigen::Index count);

}  // namespace genflow::detail
