// SPDX-License-Identifier: MIT
// A sparse Cholesky factorization in two halves, factored side by side: a vertex separator S
// cuts the graph of A into I₁ and I₂, each half's matrix [A_ii A_iS; A_Si A_SS] is factored with
// S eliminated last, and the Schur complement on S is assembled from the two factors' last
// blocks and factored densely (block elimination; docs/formulas.md §10).
#pragma once

#ifdef GENFLOW_HAS_CHOLMOD

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <functional>
#include <memory>
#include <vector>

namespace genflow::detail {

class SplitCholesky {
public:
    SplitCholesky();
    ~SplitCholesky();
    SplitCholesky(const SplitCholesky&) = delete;
    SplitCholesky& operator=(const SplitCholesky&) = delete;

    /// Analyses the pattern of A (symmetric, both triangles stored): a separator, and each
    /// half's ordering and symbolic factor, supernodal from `supernodal_switch` flops per entry
    /// of its factor. False when A does not split (a side empty), when its separator is too
    /// large to pay (its dense work above the smaller half's), or when CHOLMOD fails; the caller
    /// then factors A whole.
    [[nodiscard]] bool analyze(const Eigen::SparseMatrix<double>& A, double supernodal_switch);

    /// Factors A, of the analysed pattern, its halves on two threads when there are two and
    /// the call is not inside a parallel region (the same bits either way; supernodal halves on
    /// threads of their own, halves_side_by_side.h says why). `task`, if any, runs on the
    /// thread of the half with fewer flops, after that half: the time the other half takes
    /// longer is idle otherwise (2.5 times the flops on the 43K armadillo, 1.6 on the horse).
    /// What it throws is rethrown after the halves. False if A is not positive definite.
    [[nodiscard]] bool factorize(const Eigen::SparseMatrix<double>& A,
                                 const std::function<void()>& task = {});

    /// Analyses the supernodal halves again with wider supernodes (CHOLMOD's relaxed
    /// amalgamation allowed twice its columns), for a factor solved little: its factorization
    /// faster, its solves slower. False, the analysis kept, if CHOLMOD fails; A must be factored
    /// again.
    [[nodiscard]] bool widen_supernodes();

    /// A⁻¹·B for the last factored A; each column gets the bits it gets alone.
    [[nodiscard]] Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;

    /// Whether either half's factor is supernodal.
    [[nodiscard]] bool supernodal() const;

    /// The flops of the halves' factorization and the entries of their factors, by the last
    /// analysis (CHOLMOD's counts; the dense work on S, far smaller, left out).
    [[nodiscard]] double factor_flops() const;
    [[nodiscard]] double factor_entries() const;

    /// The rows of the separator, ascending (for tests).
    [[nodiscard]] const std::vector<int>& separator() const { return separator_; }

private:
    struct Half;

    [[nodiscard]] bool pays_for_separator() const;
    void assemble_schur_complement(const Eigen::SparseMatrix<double>& A);
    void solve_columns(const Eigen::MatrixXd& B, Eigen::Index first, int columns,
                       Eigen::MatrixXd& X) const;

    std::array<std::unique_ptr<Half>, 2> halves_;
    std::vector<int> separator_;  // A's rows in S, ascending: S's common order
    // A_SS's entries: their place in S×S (row, column) and in A's values.
    std::vector<std::array<int, 3>> separator_entries_;
    Eigen::LLT<Eigen::MatrixXd> schur_;  // of A_SS − Σ_i A_Si A_ii⁻¹ A_iS
};

}  // namespace genflow::detail

#endif
