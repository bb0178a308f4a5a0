// SPDX-License-Identifier: MIT
#include "genflow/matching/correspondence.h"

#include "genflow/exceptions.h"
#include "operators/triangle.h"

namespace genflow {

std::vector<SurfacePoint> closest_points(const Eigen::MatrixX3d& points,
                                         const TriangleMesh& target) {
    if (!detail::all_finite(points)) {
        throw InvalidInput("closest_points: the points must be finite");
    }
    const TriangleBvh bvh(target);
    std::vector<SurfacePoint> result(static_cast<std::size_t>(points.rows()));
#pragma omp parallel for schedule(dynamic, 256)
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
        result[static_cast<std::size_t>(i)] = bvh.closest_point(points.row(i).transpose());
    }
    return result;
}

}  // namespace genflow
