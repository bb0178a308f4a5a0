// SPDX-License-Identifier: MIT
// Independent reference values for the distance tests and the distance tables in bench/:
// brute-force vertex-set Hausdorff and dense surface sampling.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>

#include "genflow/mesh.h"
#include "genflow/spatial/closest_point.h"

namespace genflow::test {

/// Hausdorff distance between two point sets, by brute force (O(P·Q)).
inline double vertex_hausdorff(const Eigen::MatrixX3d& A, const Eigen::MatrixX3d& B) {
    const auto one_sided = [](const Eigen::MatrixX3d& from, const Eigen::MatrixX3d& to) {
        double worst = 0;
        for (Eigen::Index i = 0; i < from.rows(); ++i) {
            worst = std::max(worst, (to.rowwise() - from.row(i)).rowwise().norm().minCoeff());
        }
        return worst;
    };
    return std::max(one_sided(A, B), one_sided(B, A));
}

/// Distances from `from` to `to` at the points of a barycentric grid of step 1/k on every face
/// of `from` (point-to-surface distances through the BVH, itself tested against brute force).
/// `max` is a lower bound of the one-sided Hausdorff distance and within `radius` (the largest
/// spacing of the grid) of it, since the distance to a surface is 1-Lipschitz; `mean` is the
/// area-weighted mean of the samples.
struct SampledDistance {
    double max = 0;
    double mean = 0;
    double radius = 0;
};

inline SampledDistance sampled_distance(const TriangleMesh& from, const TriangleMesh& to, int k) {
    const TriangleBvh bvh(to);
    SampledDistance s;
    double area = 0;
    for (Eigen::Index f = 0; f < from.F.rows(); ++f) {
        const Eigen::Vector3d a = from.V.row(from.F(f, 0)).transpose();
        const Eigen::Vector3d b = from.V.row(from.F(f, 1)).transpose();
        const Eigen::Vector3d c = from.V.row(from.F(f, 2)).transpose();
        const double face_area = 0.5 * (b - a).cross(c - a).norm();
        s.radius =
            std::max(s.radius, std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()}) / k);
        double sum = 0;
        int count = 0;
        for (int i = 0; i <= k; ++i) {
            for (int j = 0; i + j <= k; ++j) {
                const Eigen::Vector3d p = a + (static_cast<double>(i) / k) * (b - a) +
                                          (static_cast<double>(j) / k) * (c - a);
                const double d = bvh.distance(p);
                s.max = std::max(s.max, d);
                sum += d;
                ++count;
            }
        }
        s.mean += face_area * sum / count;
        area += face_area;
    }
    s.mean /= area;
    return s;
}

}  // namespace genflow::test
