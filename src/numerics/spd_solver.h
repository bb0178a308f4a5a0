// SPDX-License-Identifier: MIT
// The one sparse SPD solver facade of genflow: CHOLMOD when the build found it, else Eigen's
// SimplicialLDLT. The symbolic analysis is kept while the sparsity pattern stays the same, so a
// flow pays for it once and only refactors numerically at each step.
#pragma once

#include <Eigen/SparseCore>
#include <functional>
#include <memory>

#include "genflow/metrics/factorization.h"

namespace genflow::detail {

class SpdSolver {
public:
    explicit SpdSolver(Factorization factorization = Factorization::BySize);
    ~SpdSolver();
    SpdSolver(SpdSolver&&) noexcept;
    SpdSolver& operator=(SpdSolver&&) noexcept;

    /// Factors A (symmetric positive definite, both triangles stored). Reuses the previous
    /// symbolic analysis when A has the same size and non-zero pattern.
    /// \throws SolverError naming `caller` if A is not numerically positive definite or holds a
    ///         non-finite entry.
    /// `task`, if any, runs meanwhile on the thread of the smaller half of a factorization in
    /// two halves, once that half is factored, else after the factorization (Metric::
    /// update_alongside()); what it throws is rethrown after the factorization.
    void compute(const Eigen::SparseMatrix<double>& A, const char* caller,
                 const std::function<void()>& task = {});

    /// A⁻¹·B for the last factored A (every column in one solve).
    [[nodiscard]] Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;

    /// How many symbolic analyses were run (for tests of the reuse).
    [[nodiscard]] int analyses() const { return analyses_; }

    /// Whether the last factorization is supernodal (for tests of the choice).
    [[nodiscard]] bool supernodal() const;

    /// Whether the last factorization was made in two halves (SplitCholesky; for tests).
    [[nodiscard]] bool split() const;

    /// Whether the factorization in two halves was analysed with wider supernodes: from the
    /// first analysis (Factorization::ByFlopDensityWide, supernodal halves), or again when its
    /// first factor's solves did less arithmetic than its factorization (for tests).
    [[nodiscard]] bool wide_supernodes() const;

    /// "CHOLMOD" or "Eigen SimplicialLDLT".
    [[nodiscard]] static const char* backend();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    int analyses_ = 0;
    Factorization factorization_;
};

}  // namespace genflow::detail
