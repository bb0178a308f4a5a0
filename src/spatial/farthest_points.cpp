// SPDX-License-Identifier: MIT
#include "spatial/farthest_points.h"

#include <algorithm>

namespace genflow::detail {

std::vector<Eigen::Index> farthest_points(const Eigen::MatrixX3d& points, Eigen::Index first,
                                          Eigen::Index count) {
    std::vector<Eigen::Index> chosen;
    if (count <= 0) {
        return chosen;
    }
    chosen.push_back(first);
    Eigen::VectorXd nearest = (points.rowwise() - points.row(first)).rowwise().norm();
    while (static_cast<Eigen::Index>(chosen.size()) < std::min(count, points.rows())) {
        Eigen::Index farthest = 0;
        if (!(nearest.maxCoeff(&farthest) > 0)) {
            break;
        }
        chosen.push_back(farthest);
        nearest = nearest.cwiseMin((points.rowwise() - points.row(farthest)).rowwise().norm());
    }
    return chosen;
}

}  // namespace genflow::detail
