// SPDX-License-Identifier: MIT
#include "genflow/operators/laplacian_eigenbasis.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "numerics/spd_solver.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

// The eigenproblem K φ = λ M φ over the vertices with mass, numbered densely (a vertex without
// mass has only zero-area, so zero, entries in K).
struct VerticesWithMass {
    Eigen::VectorXd masses;                 // of all vertices
    std::vector<Eigen::Index> kept;         // the vertices with mass
    Eigen::SparseMatrix<double> stiffness;  // K restricted to `kept`
};

VerticesWithMass vertices_with_mass(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "laplacian_eigenbasis");
    VerticesWithMass problem;
    problem.masses = lumped_masses(mesh, MassType::Barycentric);
    if (!(problem.masses.sum() > 0)) {
        throw InvalidInput("laplacian_eigenbasis: the mesh has zero area");
    }
    // Each vertex's index among `kept`, −1 if left out.
    Eigen::VectorXi dense = Eigen::VectorXi::Constant(mesh.V.rows(), -1);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        if (problem.masses[i] > 0) {
            dense[i] = static_cast<int>(problem.kept.size());
            problem.kept.push_back(i);
        }
    }
    const auto n = static_cast<Eigen::Index>(problem.kept.size());
    const Eigen::SparseMatrix<double> stiffness = cotan_stiffness(mesh);
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(stiffness.nonZeros()));
    for (Eigen::Index col = 0; col < stiffness.outerSize(); ++col) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(stiffness, col); it; ++it) {
            const int r = dense[it.row()];
            const int c = dense[it.col()];
            if (r >= 0 && c >= 0) {
                entries.emplace_back(r, c, it.value());
            }
        }
    }
    problem.stiffness.resize(n, n);
    problem.stiffness.setFromTriplets(entries.begin(), entries.end());
    return problem;
}

// Functions over the kept vertices (rows as `kept`) spread to all vertices, 0 elsewhere.
Eigen::MatrixXd on_all_vertices(const VerticesWithMass& problem, const Eigen::MatrixXd& kept,
                                Eigen::Index vertices) {
    Eigen::MatrixXd functions = Eigen::MatrixXd::Zero(vertices, kept.cols());
    for (std::size_t k = 0; k < problem.kept.size(); ++k) {
        functions.row(problem.kept[k]) = kept.row(static_cast<Eigen::Index>(k));
    }
    return functions;
}

// y = (K − σM)⁻¹ x for Spectra's shift-invert mode, with σ < 0 so that K − σM is positive
// definite and one Cholesky factorization serves every iteration.
class ShiftedInverse {
public:
    using Scalar = double;

    ShiftedInverse(const Eigen::SparseMatrix<double>& stiffness, const Eigen::VectorXd& masses)
        : stiffness_(stiffness), masses_(masses) {}

    [[nodiscard]] Eigen::Index rows() const { return stiffness_.rows(); }
    [[nodiscard]] Eigen::Index cols() const { return stiffness_.cols(); }

    void set_shift(double sigma) {
        Eigen::SparseMatrix<double> shifted = stiffness_;
        shifted.diagonal() -= sigma * masses_;
        solver_.compute(shifted, "laplacian_eigenbasis");
    }

    void perform_op(const double* x_in, double* y_out) const {
        const Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
        Eigen::Map<Eigen::VectorXd>(y_out, rows()) = solver_.solve(x);
    }

private:
    const Eigen::SparseMatrix<double>& stiffness_;
    const Eigen::VectorXd& masses_;
    detail::SpdSolver solver_;
};

// The dense solve's bound (a dense eigen-solve of 4000² takes a minute): larger meshes are
// refused, after their validation.
void require_dense_size(const TriangleMesh& mesh) {
    constexpr Eigen::Index kMaxVertices = 4000;
    if (mesh.V.rows() > kMaxVertices) {
        detail::require_valid_mesh(mesh, "laplacian_eigenbasis");
        throw InvalidInput("laplacian_eigenbasis: " + std::to_string(mesh.V.rows()) +
                           " vertices, at most " + std::to_string(kMaxVertices) +
                           " (coarsen the mesh first, or ask for the lowest eigenpairs only)");
    }
}

// All eigenpairs of `problem` (a mesh of `vertices` vertices), by a dense solve of
// K φ = λ M φ as the standard problem M^{-1/2} K M^{-1/2} ψ = λ ψ, φ = M^{-1/2} ψ.
LaplacianEigenbasis dense_basis(const VerticesWithMass& problem, Eigen::Index vertices) {
    const auto n = static_cast<Eigen::Index>(problem.kept.size());
    Eigen::VectorXd inverse_root(n);
    for (Eigen::Index k = 0; k < n; ++k) {
        inverse_root[k] = 1 / std::sqrt(problem.masses[problem.kept[static_cast<std::size_t>(k)]]);
    }
    const Eigen::MatrixXd scaled =
        inverse_root.asDiagonal() * Eigen::MatrixXd(problem.stiffness) * inverse_root.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
    if (eigen.info() != Eigen::Success) {
        throw InvalidInput("laplacian_eigenbasis: the eigen-solve did not converge");
    }
    LaplacianEigenbasis basis;
    basis.masses = problem.masses;
    basis.values = eigen.eigenvalues().cwiseMax(0);  // K is PSD: below 0 is rounding
    basis.functions =
        on_all_vertices(problem, inverse_root.asDiagonal() * eigen.eigenvectors(), vertices);
    return basis;
}

}  // namespace

LaplacianEigenbasis laplacian_eigenbasis(const TriangleMesh& mesh) {
    require_dense_size(mesh);
    return dense_basis(vertices_with_mass(mesh), mesh.V.rows());
}

LaplacianEigenbasis laplacian_eigenbasis(const TriangleMesh& mesh, Eigen::Index count) {
    if (count < 1) {
        throw InvalidInput("laplacian_eigenbasis: asked for " + std::to_string(count) +
                           " eigenpairs, at least 1");
    }
    const VerticesWithMass problem = vertices_with_mass(mesh);
    const auto n = static_cast<Eigen::Index>(problem.kept.size());
    count = std::min(count, n);
    // Lanczos keeps about twice the wanted vectors; when that is most of the space, or the mesh
    // is small anyway, the dense solve is as fast and exact.
    const Eigen::Index vectors = std::min(n, std::max(2 * count + 1, count + 20));
    if (vectors >= n || n <= 400) {
        require_dense_size(mesh);
        LaplacianEigenbasis basis = dense_basis(problem, mesh.V.rows());
        basis.values.conservativeResize(count);
        basis.functions.conservativeResize(Eigen::NoChange, count);
        return basis;
    }
    const Eigen::VectorXd kept_masses = problem.masses(problem.kept);
    // σ well below λ_1 (about 8π/area on a sphere, a few / area on a long shape), yet large
    // enough that K − σM stays well conditioned (K alone is singular).
    const double sigma = -1e-2 / kept_masses.sum();
    ShiftedInverse shifted(problem.stiffness, kept_masses);
    const Eigen::SparseMatrix<double> mass_matrix(kept_masses.asDiagonal());
    Spectra::SparseSymMatProd<double> mass_product(mass_matrix);
    Spectra::SymGEigsShiftSolver<ShiftedInverse, Spectra::SparseSymMatProd<double>,
                                 Spectra::GEigsMode::ShiftInvert>
        solver(shifted, mass_product, count, vectors, sigma);
    solver.init();
    solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-10, Spectra::SortRule::SmallestAlge);
    if (solver.info() != Spectra::CompInfo::Successful) {
        throw SolverError("laplacian_eigenbasis: the Lanczos iterations did not converge for " +
                          std::to_string(count) + " eigenpairs");
    }
    const Eigen::VectorXd values = solver.eigenvalues();
    Eigen::MatrixXd functions = solver.eigenvectors();
    // Ascending, and M-normalized (Spectra's vectors are, up to rounding).
    std::vector<Eigen::Index> order(static_cast<std::size_t>(values.size()));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](Eigen::Index a, Eigen::Index b) { return values[a] < values[b]; });
    LaplacianEigenbasis basis;
    basis.masses = problem.masses;
    basis.values = values(order).cwiseMax(0);
    functions = functions(Eigen::all, order).eval();
    for (Eigen::Index k = 0; k < functions.cols(); ++k) {
        functions.col(k) /=
            std::sqrt(functions.col(k).dot(kept_masses.asDiagonal() * functions.col(k)));
    }
    basis.functions = on_all_vertices(problem, functions, mesh.V.rows());
    return basis;
}

}  // namespace genflow
