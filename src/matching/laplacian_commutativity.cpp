// SPDX-License-Identifier: MIT
#include "genflow/matching/laplacian_commutativity.h"

#include <string>

#include "genflow/exceptions.h"

namespace genflow {

namespace {

// The share of an orthogonal map's ‖C‖²_F below which C is taken for rounding: far below any
// map that sends the surface anywhere but one point, far above double precision's noise.
constexpr double kCollapsed = 1e-9;

void check_inputs(const LaplacianEigenbasis& from_basis, const TriangleMesh& to,
                  const LaplacianEigenbasis& to_basis, const std::vector<SurfacePoint>& map,
                  Eigen::Index functions) {
    if (functions < 1) {
        throw InvalidInput("laplacian_commutativity: need at least one function, got " +
                           std::to_string(functions));
    }
    for (const auto* basis : {&from_basis, &to_basis}) {
        if (basis->values.size() <= functions || basis->functions.cols() != basis->values.size() ||
            basis->functions.rows() != basis->masses.size()) {
            throw InvalidInput("laplacian_commutativity: an eigenbasis has " +
                               std::to_string(basis->values.size()) + " pairs, need " +
                               std::to_string(functions + 1) + " with a row per vertex");
        }
    }
    if (static_cast<Eigen::Index>(map.size()) != from_basis.functions.rows() ||
        to_basis.functions.rows() != to.V.rows()) {
        throw InvalidInput("laplacian_commutativity: the map has " + std::to_string(map.size()) +
                           " points for " + std::to_string(from_basis.functions.rows()) +
                           " vertices, or the target's basis is not the target's");
    }
    for (const SurfacePoint& point : map) {
        if (point.face < 0 || point.face >= to.F.rows()) {
            throw InvalidInput("laplacian_commutativity: the map has a point on face " +
                               std::to_string(point.face) + ", the target has " +
                               std::to_string(to.F.rows()));
        }
    }
}

// ψ (columns 1..functions of `basis`) at each point of `map`, interpolated on its face.
Eigen::MatrixXd functions_at(const TriangleMesh& to, const LaplacianEigenbasis& basis,
                             const std::vector<SurfacePoint>& map, Eigen::Index functions) {
    Eigen::MatrixXd values(static_cast<Eigen::Index>(map.size()), functions);
    for (Eigen::Index i = 0; i < values.rows(); ++i) {
        const SurfacePoint& point = map[static_cast<std::size_t>(i)];
        values.row(i).setZero();
        for (int corner = 0; corner < 3; ++corner) {
            values.row(i) += point.barycentric(corner) *
                             basis.functions.row(to.F(point.face, corner)).segment(1, functions);
        }
    }
    return values;
}

}  // namespace

double laplacian_commutativity(const LaplacianEigenbasis& from_basis, const TriangleMesh& to,
                               const LaplacianEigenbasis& to_basis,
                               const std::vector<SurfacePoint>& map, Eigen::Index functions) {
    check_inputs(from_basis, to, to_basis, map, functions);
    // C = φᵀ M ψ∘π over the non-constant functions: the constant one commutes with anything.
    const Eigen::MatrixXd pulled_back = functions_at(to, to_basis, map, functions);
    const Eigen::MatrixXd C = from_basis.functions.middleCols(1, functions).transpose() *
                              (from_basis.masses.asDiagonal() * pulled_back);
    // λ·area is the same for a surface and any scaled copy of it.
    const Eigen::VectorXd from_values =
        from_basis.values.segment(1, functions) * from_basis.masses.sum();
    const Eigen::VectorXd to_values = to_basis.values.segment(1, functions) * to_basis.masses.sum();
    // A map that keeps the functions apart has ‖C‖²_F near `functions` (C orthogonal); one that
    // puts every point on one place pulls them back to 0, and what is left of C is rounding.
    if (C.squaredNorm() < kCollapsed * static_cast<double>(functions)) {
        return 1;
    }
    const Eigen::MatrixXd scaled = C * to_values.asDiagonal();
    const double norm = scaled.squaredNorm();  // 0 only if every λ_to is (many components)
    return norm > 0 ? (scaled - from_values.asDiagonal() * C).squaredNorm() / norm : 1;
}

}  // namespace genflow
