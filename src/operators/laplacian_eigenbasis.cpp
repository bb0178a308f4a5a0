// SPDX-License-Identifier: MIT
#include "genflow/operators/laplacian_eigenbasis.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <cmath>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "operators/triangle.h"

namespace genflow {

LaplacianEigenbasis laplacian_eigenbasis(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "laplacian_eigenbasis");
    constexpr Eigen::Index kMaxVertices = 4000;  // a dense eigen-solve of 4000² takes a minute
    if (mesh.V.rows() > kMaxVertices) {
        throw InvalidInput("laplacian_eigenbasis: " + std::to_string(mesh.V.rows()) +
                           " vertices, at most " + std::to_string(kMaxVertices) +
                           " (coarsen the mesh first)");
    }
    LaplacianEigenbasis basis;
    basis.masses = lumped_masses(mesh, MassType::Barycentric);
    const Eigen::VectorXd& mass = basis.masses;
    if (!(mass.sum() > 0)) {
        throw InvalidInput("laplacian_eigenbasis: the mesh has zero area");
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
        throw InvalidInput("laplacian_eigenbasis: the eigen-solve did not converge");
    }
    basis.values = eigen.eigenvalues().cwiseMax(0);  // K is PSD: below 0 is rounding
    basis.functions = Eigen::MatrixXd::Zero(mesh.V.rows(), n);
    for (Eigen::Index k = 0; k < n; ++k) {
        basis.functions.row(kept[static_cast<std::size_t>(k)]) =
            inverse_root[k] * eigen.eigenvectors().row(k);
    }
    return basis;
}

}  // namespace genflow
