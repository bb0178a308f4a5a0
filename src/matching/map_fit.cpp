// SPDX-License-Identifier: MIT
#include "matching/map_fit.h"

#include <algorithm>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/mesh/edges.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "mesh/union_find.h"
#include "metrics/metric_support.h"
#include "numerics/spd_solver.h"
#include "operators/triangle.h"

namespace genflow::detail {

Eigen::VectorXd trusted_vertices(const TriangleMesh& deformed, const Eigen::MatrixX3d& placement,
                                 double target_edge, double min_area) {
    if (placement.rows() != deformed.V.rows()) {
        throw InvalidInput("trusted_vertices: the placement has " +
                           std::to_string(placement.rows()) + " rows, not " +
                           std::to_string(deformed.V.rows()));
    }
    const auto n = static_cast<std::size_t>(deformed.V.rows());
    UnionFind pieces(n);
    const Eigen::MatrixX2i edges = unique_edges(deformed.F);
    for (Eigen::Index e = 0; e < edges.rows(); ++e) {
        const Eigen::Index a = edges(e, 0);
        const Eigen::Index b = edges(e, 1);
        const double length = (deformed.V.row(a) - deformed.V.row(b)).norm();
        if ((placement.row(a) - placement.row(b)).norm() <= kMapTear * (length + target_edge)) {
            pieces.unite(static_cast<std::size_t>(a), static_cast<std::size_t>(b));
        }
    }
    const Eigen::VectorXd masses = lumped_masses(deformed, MassType::Barycentric);
    std::vector<double> piece_area(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        piece_area[pieces.find(i)] += masses(static_cast<Eigen::Index>(i));
    }
    Eigen::VectorXd trusted(deformed.V.rows());
    for (std::size_t i = 0; i < n; ++i) {
        trusted(static_cast<Eigen::Index>(i)) = piece_area[pieces.find(i)] >= min_area ? 1 : 0;
    }
    return trusted;
}

Eigen::MatrixX3d fitted_to_map(const TriangleMesh& deformed, const Eigen::MatrixX3d& placement,
                               double length, const Eigen::VectorXd& weights) {
    if (placement.rows() != deformed.V.rows() ||
        (weights.size() > 0 && weights.size() != deformed.V.rows())) {
        throw InvalidInput("fitted_to_map: the placement or the weights have not the " +
                           std::to_string(deformed.V.rows()) + " rows of the mesh");
    }
    if (!finite_above(length, 0)) {
        throw InvalidInput("fitted_to_map: the length must be positive and finite, got " +
                           std::to_string(length));
    }
    const Eigen::VectorXd masses = lumped_masses(deformed, MassType::Barycentric);
    const Eigen::VectorXd weighted =
        weights.size() > 0 ? Eigen::VectorXd(weights.cwiseProduct(masses)) : masses;
    // The differential of ½‖X − P‖²_{WM} is W M (X − P); one step along its gradient in the
    // metric W M + λK, of length 1. A component of the mesh with no weight stays where it is:
    // the tiny ε M keeps the system definite there, with M floored as the metrics floor it, so
    // that a vertex without area (all its faces degenerate) does not make it singular.
    constexpr double kEpsilon = 1e-10;
    Eigen::SparseMatrix<double> system = length * length * cotan_stiffness(deformed);
    Eigen::SparseMatrix<double> diagonal(system.rows(), system.cols());
    diagonal.setIdentity();
    diagonal.diagonal() =
        weighted + kEpsilon * floored_lumped_masses(deformed, MassType::Barycentric);
    system += diagonal;
    SpdSolver solver;
    solver.compute(system, "fitted_to_map");
    return deformed.V + solver.solve(weighted.asDiagonal() * (placement - deformed.V));
}

namespace {

// Whether the signatures agree better after the fit by more than the share `progress`.
bool agrees_better(const FitRating& current, const FitRating& fitted, double progress) {
    return fitted.discrepancy < (1 - progress) * current.discrepancy;
}

}  // namespace

bool keeps_fit(const FitRating& current, const FitRating& fitted, double progress) {
    if (fitted.turning < std::min(0.0, current.turning)) {
        return false;
    }
    if (agrees_better(current, fitted, progress)) {
        return true;
    }
    return fitted.turning >= kMapFitRightTurning &&
           fitted.turning > current.turning + kMapFitTurningGain &&
           fitted.discrepancy <= (1 + kMapFitTurningDiscrepancy) * current.discrepancy;
}

std::optional<std::size_t> first_kept_fit(const FitRating& current,
                                          const std::vector<FitRating>& fitted, double progress) {
    for (std::size_t k = 0; k < fitted.size(); ++k) {
        const bool turns_worse = fitted[k].turning < current.turning - kMapFitTurningGain;
        // Only the first map's fit may turn them worse, and only with its signatures clearly
        // better.
        const bool excused = k == 0 && agrees_better(current, fitted[k], kMapFitProgress);
        if (keeps_fit(current, fitted[k], progress) && (!turns_worse || excused)) {
            return k;
        }
    }
    return std::nullopt;
}

}  // namespace genflow::detail
