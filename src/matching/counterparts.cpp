// SPDX-License-Identifier: MIT
#include "matching/counterparts.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/matching/correspondence.h"
#include "matching/functional_map.h"
#include "spatial/point_index.h"

namespace genflow::detail {

namespace {

// ZoomOut's first size: a map of 20 functions is coarse but right as a whole wherever the
// correspondence it is fitted to mostly is. Each step adds 4 functions, where Melzi et al.
// (2019) add 1: the positions, not the map's size, hold the counterparts in place here.
constexpr Eigen::Index kFirstSize = 20;
constexpr Eigen::Index kSizeStep = 4;

void check_inputs(const LaplacianEigenbasis& template_basis,
                  const LaplacianEigenbasis& target_basis, const TriangleMesh& target,
                  const Eigen::MatrixX3d& deformed, const CounterpartOptions& options) {
    const Eigen::Index count = template_basis.functions.cols();
    if (count < 2 || target_basis.functions.cols() != count ||
        template_basis.functions.rows() != deformed.rows() ||
        target_basis.functions.rows() != target.V.rows() ||
        template_basis.masses.size() != deformed.rows()) {
        throw InvalidInput("intrinsic_counterparts: the eigenbases (" + std::to_string(count) +
                           " and " + std::to_string(target_basis.functions.cols()) +
                           " functions) do not fit the template and the target");
    }
    // isfinite first: an ordered comparison with NaN raises the invalid-operation flag.
    if (!std::isfinite(options.reach) || options.reach <= 0) {
        throw InvalidInput("intrinsic_counterparts: reach must be positive and finite, got " +
                           std::to_string(options.reach));
    }
}

// The sizes ZoomOut fits its maps at: kFirstSize, then by kSizeStep, and `count` last.
std::vector<Eigen::Index> sizes_up_to(Eigen::Index count) {
    std::vector<Eigen::Index> sizes;
    for (Eigen::Index size = std::min(kFirstSize, count); size < count; size += kSizeStep) {
        sizes.push_back(size);
    }
    sizes.push_back(count);
    return sizes;
}

// φ √A: functions in units of the surface's own area (mean square 1 on any surface), so
// that distances between them mean the same on both shapes whatever their sizes.
Eigen::MatrixXd in_units_of_area(const LaplacianEigenbasis& basis) {
    return basis.functions * std::sqrt(basis.masses.sum());
}

// Per point, the corner of its face nearest to it: the vertex map ZoomOut starts from.
std::vector<Eigen::Index> nearest_corners(const TriangleMesh& target,
                                          const std::vector<SurfacePoint>& points) {
    std::vector<Eigen::Index> corners(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const SurfacePoint& p = points[i];
        Eigen::Index best = target.F(p.face, 0);
        for (int c = 1; c < 3; ++c) {
            const Eigen::Index v = target.F(p.face, c);
            if ((target.V.row(v).transpose() - p.point).squaredNorm() <
                (target.V.row(best).transpose() - p.point).squaredNorm()) {
                best = v;
            }
        }
        corners[i] = best;
    }
    return corners;
}

// The squared distance between row i of `a` and row j of `b` in the joint embedding.
double joint_distance2(const JointEmbedding& a, Eigen::Index i, const JointEmbedding& b,
                       Eigen::Index j, double weight2) {
    return (a.functions.row(i) - b.functions.row(j)).squaredNorm() +
           weight2 * (a.positions.row(i) - b.positions.row(j)).squaredNorm();
}

}  // namespace

// The distance D to the row `previous` bounds the answer's, and w²|x − y|² ≤ D keeps every
// target row that could be nearer. The positions weigh so much in intrinsic_counterparts() (a
// move of `reach` costs an unrelated point's mismatch) that this is a few dozen rows where the
// whole target has thousands.
std::vector<Eigen::Index> nearest_in_joint_embedding(const JointEmbedding& queries,
                                                     const JointEmbedding& targets, double weight,
                                                     const PointIndex& index,
                                                     const std::vector<Eigen::Index>& previous) {
    if (!std::isfinite(weight) || weight <= 0) {
        throw InvalidInput(
            "nearest_in_joint_embedding: the positions' weight must be positive, got " +
            std::to_string(weight));
    }
    const double weight2 = weight * weight;
    const auto count = static_cast<std::ptrdiff_t>(previous.size());
    std::vector<Eigen::Index> nearest(previous.size());
#pragma omp parallel
    {
        std::vector<std::pair<std::uint32_t, double>> near;
#pragma omp for schedule(static, 256)
        for (std::ptrdiff_t k = 0; k < count; ++k) {
            const auto i = static_cast<Eigen::Index>(k);
            Eigen::Index best = previous[static_cast<std::size_t>(k)];
            double smallest = joint_distance2(queries, i, targets, best, weight2);
            // (1 + 1e-9): rounding must not leave out a row as near as the bound.
            index.within(queries.positions.row(i).transpose(), smallest / weight2 * (1 + 1e-9),
                         near);
            for (const auto& [j, unused] : near) {
                const double d = joint_distance2(queries, i, targets, j, weight2);
                if (d < smallest || (d == smallest && j < best)) {
                    smallest = d;
                    best = j;
                }
            }
            nearest[static_cast<std::size_t>(k)] = best;
        }
    }
    return nearest;
}

Eigen::MatrixX3d closest_counterparts(const Eigen::MatrixX3d& deformed,
                                      const TriangleMesh& target) {
    return positions_of(closest_points(deformed, target));
}

Counterparts intrinsic_counterparts(const LaplacianEigenbasis& template_basis,
                                    const LaplacianEigenbasis& target_basis,
                                    const TriangleMesh& target, const Eigen::MatrixX3d& deformed,
                                    const CounterpartOptions& options) {
    check_inputs(template_basis, target_basis, target, deformed, options);
    const Eigen::MatrixXd from = in_units_of_area(template_basis);
    const Eigen::VectorXd from_masses = template_basis.masses / template_basis.masses.sum();
    const Eigen::MatrixXd to = in_units_of_area(target_basis);
    // Positions in units of the target's √area, as the functions are in units of area.
    const double unit = std::sqrt(target_basis.masses.sum());
    const std::vector<SurfacePoint> closest = closest_points(deformed, target);
    const Eigen::MatrixX3d places = positions_of(closest) / unit;
    const Eigen::MatrixX3d vertices = target.V / unit;

    const PointIndex index(vertices);

    const std::vector<Eigen::Index> start = nearest_corners(target, closest);
    std::vector<Eigen::Index> correspondence = start;
    for (const Eigen::Index size : sizes_up_to(from.cols())) {
        const Eigen::MatrixXd C =
            fitted_functional_map(from, from_masses, to, correspondence, size);
        // Two unrelated points differ by about √(2·size) in `size` functions of mean square
        // 1: a move of `reach` costs as much, so counterparts stay within about that reach.
        const double weight = std::sqrt(2.0 * static_cast<double>(size)) / options.reach;
        correspondence = nearest_in_joint_embedding({from.leftCols(size) * C, places},
                                                    {to.leftCols(size), vertices}, weight, index,
                                                    correspondence);
    }
    Counterparts counterparts{target.V(correspondence, Eigen::all), 0};
    for (std::size_t i = 0; i < start.size(); ++i) {
        counterparts.moved += correspondence[i] != start[i] ? 1 : 0;
    }
    return counterparts;
}

}  // namespace genflow::detail
