// SPDX-License-Identifier: MIT
#include "genflow/operators/heat_kernel_signature.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <cmath>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "operators/triangle.h"

namespace genflow {

std::vector<double> default_heat_kernel_times() {
    return {5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2};
}

Eigen::MatrixXd heat_kernel_signature(const TriangleMesh& mesh,
                                      const std::vector<double>& relative_times) {
    detail::require_valid_mesh(mesh, "heat_kernel_signature");
    constexpr Eigen::Index kMaxVertices = 4000;  // a dense eigen-solve of 4000² takes a minute
    if (mesh.V.rows() > kMaxVertices) {
        throw InvalidInput("heat_kernel_signature: " + std::to_string(mesh.V.rows()) +
                           " vertices, at most " + std::to_string(kMaxVertices) +
                           " (coarsen the mesh first)");
    }
    for (const double t : relative_times) {
        if (!detail::finite_above(t, 0)) {
            throw InvalidInput("heat_kernel_signature: times must be positive and finite");
        }
    }
    const Eigen::VectorXd mass = lumped_masses(mesh, MassType::Barycentric);
    const double area = mass.sum();
    if (!(area > 0)) {
        throw InvalidInput("heat_kernel_signature: the mesh has zero area");
    }
    // The vertices with mass, numbered densely.
    std::vector<Eigen::Index> kept;
    Eigen::VectorXi dense = Eigen::VectorXi::Constant(mesh.V.rows(), -1);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        if (mass[i] > 0) {
            dense[i] = static_cast<int>(kept.size());
            kept.push_back(i);
        }
    }
    const auto n = static_cast<Eigen::Index>(kept.size());
    // K φ = λ M φ as the standard problem M^{-1/2} K M^{-1/2} ψ = λ ψ, φ = M^{-1/2} ψ.
    Eigen::VectorXd inverse_root(n);
    for (Eigen::Index k = 0; k < n; ++k) {
        inverse_root[k] = 1 / std::sqrt(mass[kept[static_cast<std::size_t>(k)]]);
    }
    Eigen::MatrixXd scaled = Eigen::MatrixXd::Zero(n, n);
    const Eigen::SparseMatrix<double> stiffness = cotan_stiffness(mesh);
    for (Eigen::Index col = 0; col < stiffness.outerSize(); ++col) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(stiffness, col); it; ++it) {
            const int r = dense[it.row()];
            const int c = dense[it.col()];
            if (r >= 0 && c >= 0) {  // a zero-mass vertex has only zero-area (zero) entries
                scaled(r, c) = inverse_root[r] * it.value() * inverse_root[c];
            }
        }
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
    if (eigen.info() != Eigen::Success) {
        throw InvalidInput("heat_kernel_signature: the eigen-solve did not converge");
    }
    // φ_k(i)² = ψ_k(i)² / m_i.
    const Eigen::MatrixXd squared_modes = inverse_root.array().square().matrix().asDiagonal() *
                                          eigen.eigenvectors().array().square().matrix();
    // K is PSD: eigenvalues below 0 are rounding.
    const Eigen::VectorXd eigenvalues = eigen.eigenvalues().cwiseMax(0);

    Eigen::MatrixXd signature =
        Eigen::MatrixXd::Zero(mesh.V.rows(), static_cast<Eigen::Index>(relative_times.size()));
    for (std::size_t s = 0; s < relative_times.size(); ++s) {
        const Eigen::VectorXd decay =
            (-eigenvalues * (relative_times[s] * area)).array().exp().matrix();
        const Eigen::VectorXd column = squared_modes * decay * (area / decay.sum());
        for (Eigen::Index k = 0; k < n; ++k) {
            signature(kept[static_cast<std::size_t>(k)], static_cast<Eigen::Index>(s)) = column[k];
        }
    }
    return signature;
}

}  // namespace genflow
