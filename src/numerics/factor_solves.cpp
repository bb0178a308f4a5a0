// SPDX-License-Identifier: MIT
#include "numerics/factor_solves.h"

#ifdef GENFLOW_HAS_CHOLMOD

#include <cstddef>

namespace genflow::detail {

namespace {

// Column j of L, once its own entry has divided row j, subtracts its multiples from the rows
// below it (`rows`, `entries`: the column below the diagonal): L is read once, in the order it
// is stored.
template <int C>
void eliminate_column(double diagonal, const int* rows, const double* entries, int below,
                      double* zj, double* z) {
    double value[C];
    for (int c = 0; c < C; ++c) {
        zj[c] /= diagonal;
        value[c] = zj[c];
    }
    for (int i = 0; i < below; ++i) {
        double* zi = z + static_cast<std::ptrdiff_t>(C) * rows[i];
        const double entry = entries[i];  // read once: the stores to z may alias it
        for (int c = 0; c < C; ++c) {
            zi[c] -= entry * value[c];
        }
    }
}

// Row j of Lᵀ: column j of L below its diagonal dotted with the rows solved below, then the
// diagonal divides.
template <int C>
void substitute_row(double diagonal, const int* rows, const double* entries, int below, double* zj,
                    const double* z) {
    double sum[C] = {};
    for (int i = 0; i < below; ++i) {
        const double* zi = z + static_cast<std::ptrdiff_t>(C) * rows[i];
        for (int c = 0; c < C; ++c) {
            sum[c] += entries[i] * zi[c];
        }
    }
    for (int c = 0; c < C; ++c) {
        zj[c] = (zj[c] - sum[c]) / diagonal;
    }
}

template <int C>
void forward(const cholmod_factor& factor, double* z) {
    if (factor.is_super == 0) {
        const SimplicialColumns L(factor);
        for (int j = 0; j < L.n; ++j) {
            const int p = L.start[j];
            eliminate_column<C>(L.values[p], L.rows + p + 1, L.values + p + 1, L.count[j] - 1,
                                z + static_cast<std::ptrdiff_t>(C) * j, z);
        }
        return;
    }
    const Supernodes L(factor);
    for (int s = 0; s < L.count; ++s) {
        const auto [first, width, height, rows, block] = Supernode(L, s);
        for (int j = 0; j < width; ++j) {
            const double* column = block + static_cast<std::ptrdiff_t>(j) * height;
            eliminate_column<C>(column[j], rows + j + 1, column + j + 1, height - j - 1,
                                z + static_cast<std::ptrdiff_t>(C) * (first + j), z);
        }
    }
}

template <int C>
void backward(const cholmod_factor& factor, double* z) {
    if (factor.is_super == 0) {
        const SimplicialColumns L(factor);
        for (int j = L.n - 1; j >= 0; --j) {
            const int p = L.start[j];
            substitute_row<C>(L.values[p], L.rows + p + 1, L.values + p + 1, L.count[j] - 1,
                              z + static_cast<std::ptrdiff_t>(C) * j, z);
        }
        return;
    }
    const Supernodes L(factor);
    for (int s = L.count - 1; s >= 0; --s) {
        const auto [first, width, height, rows, block] = Supernode(L, s);
        for (int j = width - 1; j >= 0; --j) {
            const double* column = block + static_cast<std::ptrdiff_t>(j) * height;
            substitute_row<C>(column[j], rows + j + 1, column + j + 1, height - j - 1,
                              z + static_cast<std::ptrdiff_t>(C) * (first + j), z);
        }
    }
}

// Calls pass<C>(factor, z) with C = columns.
template <template <int> class Pass>
void with_columns(const cholmod_factor& factor, double* z, int columns) {
    static_assert(kFactorSolveColumns == 4, "one case per column count");
    switch (columns) {
        case 1:
            Pass<1>::run(factor, z);
            return;
        case 2:
            Pass<2>::run(factor, z);
            return;
        case 3:
            Pass<3>::run(factor, z);
            return;
        default:
            Pass<4>::run(factor, z);
            return;
    }
}

template <int C>
struct Forward {
    static void run(const cholmod_factor& factor, double* z) { forward<C>(factor, z); }
};
template <int C>
struct Backward {
    static void run(const cholmod_factor& factor, double* z) { backward<C>(factor, z); }
};

}  // namespace

bool readable_ll_factor(const cholmod_factor& factor) {
    return factor.is_ll != 0 && factor.xtype == CHOLMOD_REAL && factor.dtype == CHOLMOD_DOUBLE &&
           factor.itype == CHOLMOD_INT && factor.x != nullptr;
}

void lower_solve(const cholmod_factor& factor, double* z, int columns) {
    with_columns<Forward>(factor, z, columns);
}

void upper_solve(const cholmod_factor& factor, double* z, int columns) {
    with_columns<Backward>(factor, z, columns);
}

}  // namespace genflow::detail

#endif
