// SPDX-License-Identifier: MIT
// Solves with a supernodal CHOLMOD factor for a few right-hand sides.
#pragma once

#ifdef GENFLOW_HAS_CHOLMOD

#include <cholmod.h>

#include <Eigen/Core>

namespace genflow::detail {

/// The most right-hand sides supernodal_solve() takes; CHOLMOD's own solve, whose blocked
/// BLAS calls pay from a few more columns on, takes the rest.
constexpr Eigen::Index kSupernodalSolveColumns = 4;

/// Whether supernodal_solve() can solve with `factor` for `columns` right-hand sides: a real
/// supernodal LLᵀ factor with int indices, and 1 to kSupernodalSolveColumns columns.
[[nodiscard]] bool fits_supernodal_solve(const cholmod_factor& factor, Eigen::Index columns);

/// A⁻¹·B for L·Lᵀ = A(p, p) held in `factor` (fits_supernodal_solve() must hold). Walks the
/// factor column by column, all of B's columns at once, instead of CHOLMOD's BLAS call per
/// supernode, whose overhead dominates for a few columns: on the 48K horse's fairing matrix,
/// three columns take 7.3 instead of 10.5 ms (docs/benchmarks.md, "Supernodal solves").
[[nodiscard]] Eigen::MatrixXd supernodal_solve(const cholmod_factor& factor,
                                               const Eigen::MatrixXd& B);

}  // namespace genflow::detail

#endif
