// SPDX-License-Identifier: MIT
// Triangular solves with a CHOLMOD LLᵀ factor, simplicial or supernodal, for a few right-hand
// sides held interleaved: L⁻¹ and L⁻ᵀ apart, for the solvers that combine them with work of
// their own between the two (supernodal_solve(), SplitCholesky).
#pragma once

#ifdef GENFLOW_HAS_CHOLMOD

#include <cholmod.h>

namespace genflow::detail {

/// The most right-hand sides the passes below take at once.
constexpr int kFactorSolveColumns = 4;

/// Whether the passes below read `factor`: a real double LLᵀ factor with int indices and its
/// values, simplicial or supernodal.
[[nodiscard]] bool readable_ll_factor(const cholmod_factor& factor);

/// z := L⁻¹ z, z holding `columns` (1 … kFactorSolveColumns) columns interleaved (row k of the
/// factor's order at z[columns·k]). Each column gets the bits it gets alone.
void lower_solve(const cholmod_factor& factor, double* z, int columns);

/// z := L⁻ᵀ z, as lower_solve().
void upper_solve(const cholmod_factor& factor, double* z, int columns);

}  // namespace genflow::detail

#endif
