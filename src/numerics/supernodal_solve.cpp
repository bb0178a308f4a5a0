// SPDX-License-Identifier: MIT
#include "numerics/supernodal_solve.h"

#ifdef GENFLOW_HAS_CHOLMOD

#include <cstddef>
#include <vector>

namespace genflow::detail {

namespace {

// A supernodal factor's arrays. Supernode s holds the columns first_column[s] … first_column[s
// + 1] − 1; its rows are rows[row_start[s] …], the first of them its own columns in order, and
// its values, from values[value_start[s]], are column-major with one entry per row.
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

// Supernode s of a factor: its first column, how many columns and rows, the rows' indices and
// its column-major values.
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

// z := L⁻¹ z, z holding C columns interleaved (row k at z[C·k]). Column j of L, once its own
// entry has divided row j, subtracts its multiples from the rows below it: L is read once, in
// the order it is stored.
template <int C>
void forward(const Supernodes& L, double* z) {
    for (int s = 0; s < L.count; ++s) {
        const auto [first, width, height, rows, block] = Supernode(L, s);
        for (int j = 0; j < width; ++j) {
            const double* column = block + static_cast<std::ptrdiff_t>(j) * height;
            double* zj = z + static_cast<std::ptrdiff_t>(C) * (first + j);
            double value[C];
            for (int c = 0; c < C; ++c) {
                zj[c] /= column[j];
                value[c] = zj[c];
            }
            for (int i = j + 1; i < height; ++i) {
                double* zi = z + static_cast<std::ptrdiff_t>(C) * rows[i];
                const double entry = column[i];  // read once: the stores to z may alias it
                for (int c = 0; c < C; ++c) {
                    zi[c] -= entry * value[c];
                }
            }
        }
    }
}

// z := L⁻ᵀ z: row j of Lᵀ, last to first, is column j of L dotted with the rows solved below.
template <int C>
void backward(const Supernodes& L, double* z) {
    for (int s = L.count - 1; s >= 0; --s) {
        const auto [first, width, height, rows, block] = Supernode(L, s);
        for (int j = width - 1; j >= 0; --j) {
            const double* column = block + static_cast<std::ptrdiff_t>(j) * height;
            double sum[C] = {};
            for (int i = j + 1; i < height; ++i) {
                const double* zi = z + static_cast<std::ptrdiff_t>(C) * rows[i];
                for (int c = 0; c < C; ++c) {
                    sum[c] += column[i] * zi[c];
                }
            }
            double* zj = z + static_cast<std::ptrdiff_t>(C) * (first + j);
            for (int c = 0; c < C; ++c) {
                zj[c] = (zj[c] - sum[c]) / column[j];
            }
        }
    }
}

// X = A⁻¹ B = Pᵀ L⁻ᵀ L⁻¹ P B, with (P B)_k = B_{perm[k]}.
template <int C>
Eigen::MatrixXd solve(const cholmod_factor& factor, const Eigen::MatrixXd& B) {
    const auto n = static_cast<Eigen::Index>(factor.n);
    const auto* perm = static_cast<const int*>(factor.Perm);
    const auto row_of = [perm](Eigen::Index k) { return perm != nullptr ? perm[k] : k; };
    std::vector<double> z(static_cast<std::size_t>(C * n));
    for (Eigen::Index k = 0; k < n; ++k) {
        for (int c = 0; c < C; ++c) {
            z[static_cast<std::size_t>(C * k + c)] = B(row_of(k), c);
        }
    }
    const Supernodes L(factor);
    forward<C>(L, z.data());
    backward<C>(L, z.data());
    Eigen::MatrixXd X(n, C);
    for (Eigen::Index k = 0; k < n; ++k) {
        for (int c = 0; c < C; ++c) {
            X(row_of(k), c) = z[static_cast<std::size_t>(C * k + c)];
        }
    }
    return X;
}

}  // namespace

bool fits_supernodal_solve(const cholmod_factor& factor, Eigen::Index columns) {
    return factor.is_super != 0 && factor.is_ll != 0 && factor.xtype == CHOLMOD_REAL &&
           factor.dtype == CHOLMOD_DOUBLE && factor.itype == CHOLMOD_INT && factor.x != nullptr &&
           columns >= 1 && columns <= kSupernodalSolveColumns;
}

Eigen::MatrixXd supernodal_solve(const cholmod_factor& factor, const Eigen::MatrixXd& B) {
    static_assert(kSupernodalSolveColumns == 4, "one case per column count");
    switch (B.cols()) {
        case 1:
            return solve<1>(factor, B);
        case 2:
            return solve<2>(factor, B);
        case 3:
            return solve<3>(factor, B);
        default:
            return solve<4>(factor, B);
    }
}

}  // namespace genflow::detail

#endif
