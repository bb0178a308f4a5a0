// SPDX-License-Identifier: MIT
// Reading a CHOLMOD LLᵀ factor, simplicial or supernodal: views of its arrays, a walk over its
// entries, and triangular solves for a few right-hand sides held interleaved, L⁻¹ and L⁻ᵀ apart,
// for the solvers that combine them with work of their own between the two (supernodal_solve(),
// SplitCholesky).
#pragma once

#ifdef GENFLOW_HAS_CHOLMOD

#include <cholmod.h>

#include <algorithm>
#include <cstddef>

namespace genflow::detail {

/// A supernodal factor's arrays. Supernode s holds the columns first_column[s] … first_column[s
/// + 1] − 1; its rows are rows[row_start[s] …], the first of them its own columns in order, and
/// its values, from values[value_start[s]], are column-major with one entry per row.
struct Supernodes {
    int count;
    const int* first_column;
    const int* row_start;
    const int* value_start;
    const int* rows;
    const double* values;

    explicit Supernodes(const cholmod_factor& factor)
        : count(static_cast<int>(factor.nsuper)),
          first_column(static_cast<const int*>(factor.super)),
          row_start(static_cast<const int*>(factor.pi)),
          value_start(static_cast<const int*>(factor.px)),
          rows(static_cast<const int*>(factor.s)),
          values(static_cast<const double*>(factor.x)) {}
};

/// Supernode s of a factor: its first column, how many columns and rows, the rows' indices and
/// its column-major values.
struct Supernode {
    int first;
    int width;
    int height;
    const int* rows;
    const double* block;

    Supernode(const Supernodes& L, int s)
        : first(L.first_column[s]),
          width(L.first_column[s + 1] - first),
          height(L.row_start[s + 1] - L.row_start[s]),
          rows(L.rows + L.row_start[s]),
          block(L.values + L.value_start[s]) {}
};

/// A simplicial factor's arrays: column j has count[j] entries from start[j], the diagonal first.
struct SimplicialColumns {
    int n;
    const int* start;
    const int* count;
    const int* rows;
    const double* values;

    explicit SimplicialColumns(const cholmod_factor& factor)
        : n(static_cast<int>(factor.n)),
          start(static_cast<const int*>(factor.p)),
          count(static_cast<const int*>(factor.nz)),
          rows(static_cast<const int*>(factor.i)),
          values(static_cast<const double*>(factor.x)) {}
};

/// Calls visit(row, column, value) for each stored entry of L on or below its diagonal in the
/// columns from `first_column` on, column by column (rows and columns in the factor's order).
template <typename Visit>
void for_each_lower_entry(const cholmod_factor& factor, int first_column, Visit&& visit) {
    if (factor.is_super == 0) {
        const SimplicialColumns L(factor);
        for (int j = first_column; j < L.n; ++j) {
            for (int p = L.start[j]; p < L.start[j] + L.count[j]; ++p) {
                visit(L.rows[p], j, L.values[p]);
            }
        }
        return;
    }
    const Supernodes L(factor);
    for (int s = 0; s < L.count; ++s) {
        const auto [first, width, height, rows, block] = Supernode(L, s);
        for (int j = std::max(first, first_column); j < first + width; ++j) {
            const double* column = block + static_cast<std::ptrdiff_t>(j - first) * height;
            for (int i = j - first; i < height; ++i) {
                visit(rows[i], j, column[i]);
            }
        }
    }
}

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
