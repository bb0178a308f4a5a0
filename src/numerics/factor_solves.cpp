// SPDX-License-Identifier: MIT
#include "numerics/factor_solves.h"

#ifdef GENFLOW_HAS_CHOLMOD

#include <algorithm>
#include <cstddef>
#include <vector>

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

// The most rows any supernode of L holds below its own columns.
int most_rows_below(const Supernodes& L) {
    int most = 0;
    for (int s = 0; s < L.count; ++s) {
        const Supernode node(L, s);
        most = std::max(most, node.height - node.width);
    }
    return most;
}

// A supernode's rows below its own columns, their values in z copied into `below` (packed, in
// the supernode's row order) and back: its columns then read and update them there, gathered
// from z's scattered rows once for the supernode instead of once a column.
template <int C>
void gather_rows_below(const Supernode& node, const double* z, double* below) {
    for (int t = 0; t < node.height - node.width; ++t) {
        const double* zi = z + static_cast<std::ptrdiff_t>(C) * node.rows[node.width + t];
        for (int c = 0; c < C; ++c) {
            below[C * t + c] = zi[c];
        }
    }
}

template <int C>
void scatter_rows_below(const Supernode& node, const double* below, double* z) {
    for (int t = 0; t < node.height - node.width; ++t) {
        double* zi = z + static_cast<std::ptrdiff_t>(C) * node.rows[node.width + t];
        for (int c = 0; c < C; ++c) {
            zi[c] = below[C * t + c];
        }
    }
}

// rows_z[C·i + c] -= entries[i] · solved[c] for i below `count`: a solved column's multiples
// taken from packed rows.
template <int C>
void subtract_multiples(const double* entries, int count, const double* solved, double* rows_z) {
    double value[C];
    for (int c = 0; c < C; ++c) {
        value[c] = solved[c];
    }
    for (int i = 0; i < count; ++i) {
        const double entry = entries[i];
        for (int c = 0; c < C; ++c) {
            rows_z[C * i + c] -= entry * value[c];
        }
    }
}

// sum[c] += entries[i] · rows_z[C·i + c] for i below `count`, in order.
template <int C>
void add_products(const double* entries, int count, const double* rows_z, double* sum) {
    for (int i = 0; i < count; ++i) {
        for (int c = 0; c < C; ++c) {
            sum[c] += entries[i] * rows_z[C * i + c];
        }
    }
}

// The widest supernode of L.
int widest_supernode(const Supernodes& L) {
    int widest = 0;
    for (int s = 0; s < L.count; ++s) {
        widest = std::max(widest, L.first_column[s + 1] - L.first_column[s]);
    }
    return widest;
}

// sums[C·j + c] := Σ_t column_j[width + t] · below[C·t + c] for K of the node's columns from j:
// their K·C sums are independent chains of additions, which advance side by side.
template <int C, int K>
void products_below_of(const Supernode& node, int j, const double* below, double* sums) {
    double sum[K][C] = {};
    const double* first = node.block + static_cast<std::ptrdiff_t>(j) * node.height + node.width;
    for (int t = 0; t < node.height - node.width; ++t) {
        for (int k = 0; k < K; ++k) {
            const double entry = first[static_cast<std::ptrdiff_t>(k) * node.height + t];
            for (int c = 0; c < C; ++c) {
                sum[k][c] += entry * below[C * t + c];
            }
        }
    }
    for (int k = 0; k < K; ++k) {
        for (int c = 0; c < C; ++c) {
            sums[C * (j + k) + c] = sum[k][c];
        }
    }
}

// products_below_of() for all the node's columns, four at a time: with three right-hand sides,
// twelve chains keep the adder busy through its latency and their sums in registers.
template <int C>
void products_below(const Supernode& node, const double* below, double* sums) {
    constexpr int kSideBySide = 4;
    static_assert(kSideBySide == 4, "one case per remainder below");
    int j = 0;
    for (; j + kSideBySide <= node.width; j += kSideBySide) {
        products_below_of<C, kSideBySide>(node, j, below, sums);
    }
    switch (node.width - j) {
        case 3:
            products_below_of<C, 3>(node, j, below, sums);
            return;
        case 2:
            products_below_of<C, 2>(node, j, below, sums);
            return;
        case 1:
            products_below_of<C, 1>(node, j, below, sums);
            return;
        default:
            return;
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
    // Column j of a supernode: divided by its diagonal, then its multiples off the rows of its
    // own block below j (contiguous in z) and off the rows below the block (packed): the
    // arithmetic of a walk column by column, and so its bits.
    const Supernodes L(factor);
    std::vector<double> below(static_cast<std::size_t>(C * most_rows_below(L)));
    for (int s = 0; s < L.count; ++s) {
        const Supernode node(L, s);
        gather_rows_below<C>(node, z, below.data());
        for (int j = 0; j < node.width; ++j) {
            const double* column = node.block + static_cast<std::ptrdiff_t>(j) * node.height;
            double* zj = z + static_cast<std::ptrdiff_t>(C) * (node.first + j);
            for (int c = 0; c < C; ++c) {
                zj[c] /= column[j];
            }
            subtract_multiples<C>(column + j + 1, node.width - j - 1, zj, zj + C);
            subtract_multiples<C>(column + node.width, node.height - node.width, zj, below.data());
        }
        scatter_rows_below<C>(node, below.data(), z);
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
    // Row j of a supernode's Lᵀ: its products with the rows below the block (packed, solved by
    // the supernodes after this one), found for all the block's columns at once, then with the
    // rows of the block below j; then the diagonal divides. The columns' sums over the rows below
    // are independent, so they advance side by side instead of as one chain of additions.
    const Supernodes L(factor);
    std::vector<double> below(static_cast<std::size_t>(C * most_rows_below(L)));
    std::vector<double> sums(static_cast<std::size_t>(C * widest_supernode(L)));
    for (int s = L.count - 1; s >= 0; --s) {
        const Supernode node(L, s);
        gather_rows_below<C>(node, z, below.data());
        products_below<C>(node, below.data(), sums.data());
        for (int j = node.width - 1; j >= 0; --j) {
            const double* column = node.block + static_cast<std::ptrdiff_t>(j) * node.height;
            double* zj = z + static_cast<std::ptrdiff_t>(C) * (node.first + j);
            double* sum = sums.data() + static_cast<std::ptrdiff_t>(C) * j;
            add_products<C>(column + j + 1, node.width - j - 1, zj + C, sum);
            for (int c = 0; c < C; ++c) {
                zj[c] = (zj[c] - sum[c]) / column[j];
            }
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
