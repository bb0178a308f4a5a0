// SPDX-License-Identifier: MIT
#include "genflow/matching/correspondence.h"

#include <string>

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

std::vector<SurfacePoint> match_correspondence(const MatchResult& result,
                                               const TriangleMesh& target) {
    if (result.counterparts.rows() != result.deformed.V.rows()) {
        throw InvalidInput("match_correspondence: " + std::to_string(result.counterparts.rows()) +
                           " counterparts for " + std::to_string(result.deformed.V.rows()) +
                           " template vertices");
    }
    if (!result.counterparts_moved) {
        // The stage did not run: the counterparts are the closest points, found again here with
        // their faces and distances as they are.
        return closest_points(result.deformed.V, target);
    }
    std::vector<SurfacePoint> points = closest_points(result.counterparts, target);
    for (std::size_t i = 0; i < points.size(); ++i) {
        points[i].distance =
            (result.deformed.V.row(static_cast<Eigen::Index>(i)).transpose() - points[i].point)
                .norm();
    }
    return points;
}

}  // namespace genflow
