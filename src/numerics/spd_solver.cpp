// SPDX-License-Identifier: MIT
#include "numerics/spd_solver.h"

#include <string>
#include <vector>

#include "genflow/exceptions.h"

#ifdef GENFLOW_HAS_CHOLMOD
#include <Eigen/CholmodSupport>
#else
#include <Eigen/SparseCholesky>
#endif

namespace genflow::detail {

struct SpdSolver::Impl {
#ifdef GENFLOW_HAS_CHOLMOD
    // Supernodal or simplicial as CHOLMOD decides (CHOLMOD_AUTO), LLᵀ.
    Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower> solver;
#else
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> solver;
#endif
    Eigen::Index rows = -1;
    std::vector<Eigen::SparseMatrix<double>::StorageIndex> outer;
    std::vector<Eigen::SparseMatrix<double>::StorageIndex> inner;
    bool factored = false;

    bool same_pattern(const Eigen::SparseMatrix<double>& A) const {
        return A.rows() == rows && static_cast<std::size_t>(A.nonZeros()) == inner.size() &&
               std::equal(outer.begin(), outer.end(), A.outerIndexPtr()) &&
               std::equal(inner.begin(), inner.end(), A.innerIndexPtr());
    }
};

SpdSolver::SpdSolver() : impl_(std::make_unique<Impl>()) {}
SpdSolver::~SpdSolver() = default;
SpdSolver::SpdSolver(SpdSolver&&) noexcept = default;
SpdSolver& SpdSolver::operator=(SpdSolver&&) noexcept = default;

const char* SpdSolver::backend() {
#ifdef GENFLOW_HAS_CHOLMOD
    return "CHOLMOD";
#else
    return "Eigen SimplicialLDLT";
#endif
}

void SpdSolver::compute(const Eigen::SparseMatrix<double>& A, const char* caller) {
    if (A.rows() != A.cols()) {
        throw SolverError(std::string(caller) + ": matrix is not square");
    }
    for (Eigen::Index k = 0; k < A.nonZeros(); ++k) {
        if (!std::isfinite(A.valuePtr()[k])) {
            throw SolverError(
                std::string(caller) +
                ": matrix has a non-finite entry (non-finite positions or parameters?)");
        }
    }
    Eigen::SparseMatrix<double> compressed = A;
    compressed.makeCompressed();
    if (!impl_->same_pattern(compressed)) {
        impl_->solver.analyzePattern(compressed);
        impl_->rows = compressed.rows();
        impl_->outer.assign(compressed.outerIndexPtr(),
                            compressed.outerIndexPtr() + compressed.outerSize() + 1);
        impl_->inner.assign(compressed.innerIndexPtr(),
                            compressed.innerIndexPtr() + compressed.nonZeros());
        ++analyses_;
    }
    impl_->solver.factorize(compressed);
    impl_->factored = impl_->solver.info() == Eigen::Success;
#ifndef GENFLOW_HAS_CHOLMOD
    // LDLᵀ succeeds on indefinite matrices; a non-positive pivot means A is not SPD.
    if (impl_->factored && (impl_->solver.vectorD().array() <= 0).any()) {
        impl_->factored = false;
    }
#endif
    if (!impl_->factored) {
        throw SolverError(std::string(caller) +
                          ": matrix is not positive definite (degenerate mesh, isolated vertices "
                          "with zero mass, or a non-positive parameter?)");
    }
}

Eigen::MatrixXd SpdSolver::solve(const Eigen::MatrixXd& B) const {
    if (!impl_->factored || B.rows() != impl_->rows) {
        throw InvalidInput("SpdSolver::solve: no factorization of a matching size");
    }
    Eigen::MatrixXd X(B.rows(), B.cols());
    for (Eigen::Index c = 0; c < B.cols(); ++c) {
        X.col(c) = impl_->solver.solve(Eigen::VectorXd(B.col(c)));
    }
    return X;
}

}  // namespace genflow::detail
