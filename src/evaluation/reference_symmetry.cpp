// SPDX-License-Identifier: MIT
#include "genflow/evaluation/reference_symmetry.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "genflow/exceptions.h"
#include "spatial/point_index.h"

namespace genflow {

namespace {

// The plane fit alternates this many times; it settles in a few (measured on FAUST: the
// residual no longer changes after 8).
constexpr int kPlaneIterations = 15;
// The fit runs on every stride-th reference point, at most this many of them: enough points to
// pin a plane, and the search over a set stays a few seconds.
constexpr Eigen::Index kFitPoints = 400;

struct Plane {
    Eigen::Vector3d normal;
    Eigen::Vector3d point;
};

Eigen::Vector3d reflected(const Eigen::Vector3d& x, const Plane& plane) {
    return x - 2 * plane.normal.dot(x - plane.point) * plane.normal;
}

struct Fit {
    Plane plane;
    double residual = std::numeric_limits<double>::infinity();  // RMS, in the points' units
};

// From one starting normal: mirror each fit point, pair it with the nearest point, then take as
// normal the direction along which the pairs differ most (the principal axis of their
// differences) and as plane point their midpoints' median offset along it.
Fit fit_plane(const Eigen::MatrixX3d& points, const std::vector<Eigen::Index>& fit_rows,
              const detail::PointIndex& index, const Eigen::Vector3d& start) {
    Fit fit;
    fit.plane = {start.normalized(), points.colwise().mean().transpose()};
    std::vector<double> offsets(fit_rows.size());
    for (int iteration = 0; iteration <= kPlaneIterations; ++iteration) {
        Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
        double squared = 0;
        for (std::size_t i = 0; i < fit_rows.size(); ++i) {
            const Eigen::Vector3d x = points.row(fit_rows[i]).transpose();
            const auto [mate, distance2] = index.nearest(reflected(x, fit.plane));
            const Eigen::Vector3d y = points.row(static_cast<Eigen::Index>(mate)).transpose();
            scatter += (x - y) * (x - y).transpose();
            offsets[i] = fit.plane.normal.dot(0.5 * (x + y) - fit.plane.point);
            squared += distance2;
        }
        fit.residual = std::sqrt(squared / static_cast<double>(fit_rows.size()));
        if (iteration == kPlaneIterations) {
            break;
        }
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> axes(scatter);
        Eigen::Vector3d normal = axes.eigenvectors().col(2);
        if (normal.dot(fit.plane.normal) < 0) {
            normal = -normal;
        }
        std::nth_element(offsets.begin(),
                         offsets.begin() + static_cast<std::ptrdiff_t>(offsets.size() / 2),
                         offsets.end());
        fit.plane.point += offsets[offsets.size() / 2] * fit.plane.normal;
        fit.plane.normal = normal;
    }
    return fit;
}

// The best plane of one shape's points, from each principal axis.
Fit best_plane(const Eigen::MatrixX3d& points, const std::vector<Eigen::Index>& fit_rows) {
    const detail::PointIndex index(points);
    const Eigen::MatrixX3d centred = points.rowwise() - points.colwise().mean();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> axes(centred.transpose() * centred);
    Fit best;
    for (int axis = 0; axis < 3; ++axis) {
        Fit fit = fit_plane(points, fit_rows, index, axes.eigenvectors().col(axis));
        if (fit.residual < best.residual) {
            best = fit;
        }
    }
    return best;
}

}  // namespace

ReferenceSymmetry estimate_reference_symmetry(const std::vector<Eigen::MatrixX3d>& positions,
                                              const std::vector<double>& units) {
    if (positions.empty() || units.size() != positions.size() || positions.front().rows() < 4) {
        throw InvalidInput(
            "estimate_reference_symmetry: need shapes with at least 4 reference points and a "
            "unit for each");
    }
    const Eigen::Index count = positions.front().rows();
    for (std::size_t s = 0; s < positions.size(); ++s) {
        if (positions[s].rows() != count || !(units[s] > 0)) {
            throw InvalidInput("estimate_reference_symmetry: shape " + std::to_string(s) + " has " +
                               std::to_string(positions[s].rows()) +
                               " reference points (the first has " + std::to_string(count) +
                               ") or no positive unit");
        }
    }
    const Eigen::Index stride = std::max<Eigen::Index>(1, count / kFitPoints);
    std::vector<Eigen::Index> fit_rows;
    for (Eigen::Index k = 0; k < count; k += stride) {
        fit_rows.push_back(k);
    }
    std::vector<Fit> fits(positions.size());
#pragma omp parallel for schedule(dynamic)
    for (std::size_t s = 0; s < positions.size(); ++s) {
        fits[s] = best_plane(positions[s], fit_rows);
    }
    ReferenceSymmetry symmetry;
    symmetry.residual = std::numeric_limits<double>::infinity();
    for (std::size_t s = 0; s < positions.size(); ++s) {
        if (fits[s].residual / units[s] < symmetry.residual) {
            symmetry.residual = fits[s].residual / units[s];
            symmetry.shape = static_cast<Eigen::Index>(s);
        }
    }
    if (symmetry.residual > kSymmetryTolerance) {
        return symmetry;
    }
    const Eigen::MatrixX3d& points = positions[static_cast<std::size_t>(symmetry.shape)];
    const Plane& plane = fits[static_cast<std::size_t>(symmetry.shape)].plane;
    const detail::PointIndex index(points);
    symmetry.mirror.resize(static_cast<std::size_t>(count));
    for (Eigen::Index k = 0; k < count; ++k) {
        symmetry.mirror[static_cast<std::size_t>(k)] = static_cast<Eigen::Index>(
            index.nearest(reflected(points.row(k).transpose(), plane)).first);
    }
    return symmetry;
}

}  // namespace genflow
