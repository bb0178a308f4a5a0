// SPDX-License-Identifier: MIT
#include "numerics/split_cholesky.h"

#ifdef GENFLOW_HAS_CHOLMOD

#include <cholmod.h>

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <array>
#include <exception>
#include <utility>

#include "numerics/factor_solves.h"
#include "numerics/halves_side_by_side.h"

namespace genflow::detail {

namespace {

constexpr int kInterior = 0;   // cholmod_camd()'s constraint set of the interior rows
constexpr int kSeparator = 1;  // … and of the separator's, eliminated after them
constexpr int kCut = 2;        // cholmod_bisect()'s mark of a separator row

}  // namespace

// One half: its rows of A (its interior, then S in the common order), its matrix in the order of
// its factor, with, per entry, the place in A's values it is copied from, and its factor.
struct SplitCholesky::Half {
    cholmod_common common{};
    std::vector<int> rows;
    int interior = 0;
    // The lower triangle of the half's matrix in its rows' order, each entry's value its place
    // in A's values (exact in a double).
    cholmod_sparse* places = nullptr;
    std::vector<int> order;  // CAMD's, the separator last: the factor's row k is rows[order[k]]
    // The half's matrix as cholmod_factorize() hands it to the numeric factorization (see
    // arrange()), and per entry the place in A's values.
    cholmod_sparse* matrix = nullptr;
    std::vector<Eigen::Index> source;
    cholmod_factor* factor = nullptr;
    // The factor's last |S| columns, L_S (lower triangular), rows and columns in the factor's
    // order of S; separator_slot[t] is the common slot of its row t.
    Eigen::MatrixXd last_block;
    std::vector<int> separator_slot;

    Half() {
        cholmod_start(&common);
        common.print = 0;  // failures are reported by the caller
    }
    ~Half() {
        cholmod_free_factor(&factor, &common);
        cholmod_free_sparse(&matrix, &common);
        cholmod_free_sparse(&places, &common);
        cholmod_finish(&common);
    }
    Half(const Half&) = delete;
    Half& operator=(const Half&) = delete;

    [[nodiscard]] int size() const { return static_cast<int>(rows.size()); }

    void gather_places(const Eigen::SparseMatrix<double>& A, const std::vector<int>& local);
    [[nodiscard]] bool analyze(double supernodal_switch);
    [[nodiscard]] bool analyze_symbolic();
    [[nodiscard]] bool arrange(bool supernodal);
    [[nodiscard]] bool widen_supernodes();
    [[nodiscard]] bool factorize(const Eigen::SparseMatrix<double>& A);
    void read_last_block();

    // z: the interior rows of columns first … first + columns − 1 of B in the factor's order
    // (interleaved), zeros for S; then z := L⁻¹ z.
    void forward(const Eigen::MatrixXd& B, Eigen::Index first, int columns,
                 std::vector<double>& z) const;
    // rhs (S's common order) += L_S q, q the S rows of z after forward().
    void push_separator(const std::vector<double>& z, int columns, Eigen::MatrixXd& rhs) const;
    // z's S rows := L_Sᵀ x_S, then z := L⁻ᵀ z, whose interior rows go to X's columns from `first`.
    void backward(const Eigen::MatrixXd& x_s, std::vector<double>& z, Eigen::Index first,
                  Eigen::MatrixXd& X) const;
};

// `places`: the lower triangle of A restricted to `rows`, renumbered by `local` (A's row → this
// half's, −1 outside it), each column sorted.
void SplitCholesky::Half::gather_places(const Eigen::SparseMatrix<double>& A,
                                        const std::vector<int>& local) {
    std::vector<std::pair<int, Eigen::Index>> column;  // (local row, place in A's values)
    std::vector<int> starts{0};
    std::vector<int> entries;
    std::vector<double> values;
    for (int c = 0; c < size(); ++c) {
        column.clear();
        const int a = rows[static_cast<std::size_t>(c)];
        for (Eigen::Index k = A.outerIndexPtr()[a]; k < A.outerIndexPtr()[a + 1]; ++k) {
            const int r = local[static_cast<std::size_t>(A.innerIndexPtr()[k])];
            if (r >= c) {
                column.emplace_back(r, k);
            }
        }
        std::sort(column.begin(), column.end());
        for (const auto& [r, k] : column) {
            entries.push_back(r);
            values.push_back(static_cast<double>(k));
        }
        starts.push_back(static_cast<int>(entries.size()));
    }
    const auto n = static_cast<std::size_t>(size());
    places = cholmod_allocate_sparse(n, n, entries.size(), 1, 1, -1, CHOLMOD_REAL, &common);
    std::copy(starts.begin(), starts.end(), static_cast<int*>(places->p));
    std::copy(entries.begin(), entries.end(), static_cast<int*>(places->i));
    std::copy(values.begin(), values.end(), static_cast<double*>(places->x));
}

// An ordering with S last (CAMD, constrained), then the symbolic factor of the matrix in that
// order.
bool SplitCholesky::Half::analyze(double supernodal_switch) {
    std::vector<int> set(rows.size(), kSeparator);
    std::fill(set.begin(), set.begin() + interior, kInterior);
    order.resize(rows.size());
    if (!cholmod_camd(places, nullptr, 0, set.data(), order.data(), &common)) {
        return false;
    }
    separator_slot.clear();
    for (int k = interior; k < size(); ++k) {
        if (order[static_cast<std::size_t>(k)] < interior) {
            return false;
        }
        separator_slot.push_back(order[static_cast<std::size_t>(k)] - interior);
    }
    // The matrix is put in CAMD's order, which is postordered within its constraints; CHOLMOD's
    // own postorder could move a separator row that no interior row reaches ahead of them.
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_NATURAL;
    common.postorder = 0;
    common.supernodal = CHOLMOD_AUTO;
    common.supernodal_switch = supernodal_switch;
    common.final_asis = 0;
    common.final_ll = 1;
    return arrange(true) && analyze_symbolic();
}

// The symbolic factor of `matrix`, replacing the one before if it succeeds; then the matrix
// arranged for its kind.
bool SplitCholesky::Half::analyze_symbolic() {
    cholmod_factor* analysed = cholmod_analyze(matrix, &common);
    if (analysed == nullptr) {
        return false;
    }
    cholmod_free_factor(&factor, &common);
    factor = analysed;
    return arrange(factor->is_super != 0);
}

// `matrix` as cholmod_factorize() would arrange the half's lower triangle in `order` before its
// numeric factorization: tril(PAPᵀ) for a supernodal factor, triu(PAPᵀ) for a simplicial one,
// each made by CHOLMOD's own transposes (once here, with the entries' places as values) so that
// the factorization, given the factor in its natural order, reads it as it is and rounds as
// before. That spares two transposes a factorization (docs/benchmarks.md, "Two halves").
bool SplitCholesky::Half::arrange(bool supernodal) {
    if (matrix != nullptr && (matrix->stype < 0) == supernodal) {
        return true;
    }
    cholmod_sparse* upper = cholmod_ptranspose(places, 2, order.data(), nullptr, 0, &common);
    cholmod_sparse* arranged = supernodal && upper != nullptr
                                   ? cholmod_ptranspose(upper, 2, nullptr, nullptr, 0, &common)
                                   : upper;
    if (arranged != upper) {
        cholmod_free_sparse(&upper, &common);
    }
    if (arranged == nullptr) {
        return false;
    }
    cholmod_free_sparse(&matrix, &common);
    matrix = arranged;
    const auto* place = static_cast<const double*>(matrix->x);
    source.resize(static_cast<std::size_t>(cholmod_nnz(matrix, &common)));
    for (std::size_t e = 0; e < source.size(); ++e) {
        source[e] = static_cast<Eigen::Index>(place[e]);
    }
    return true;
}

// Twice CHOLMOD's column limits of relaxed amalgamation (its `nrelax`, 4, 16 and 48 columns):
// on the horse's halves a factorization 31.5–33.1 → 25.3–25.8 ms, a three-column solve 4.4–4.6
// → 6.8–7.0 ms; four times made the factorization no faster and the solves slower
// (docs/benchmarks.md, "Two halves").
bool SplitCholesky::Half::widen_supernodes() {
    // A simplicial factor has no supernodes, and its analysis would come out the same: the kind
    // is chosen by flops per entry of the factor, before any amalgamation.
    if (factor->is_super == 0) {
        return true;
    }
    constexpr std::array<std::size_t, 3> kWideRelaxation{8, 32, 96};
    std::copy(kWideRelaxation.begin(), kWideRelaxation.end(), common.nrelax);
    return analyze_symbolic();
}

bool SplitCholesky::Half::factorize(const Eigen::SparseMatrix<double>& A) {
    auto* values = static_cast<double*>(matrix->x);
    for (std::size_t e = 0; e < source.size(); ++e) {
        values[e] = A.valuePtr()[source[e]];
    }
    const bool factored = cholmod_factorize(matrix, factor, &common) != 0 &&
                          common.status == CHOLMOD_OK && factor->minor == factor->n;
    if (factored) {
        read_last_block();
    }
    return factored;
}

// L_S from the factor's columns interior … n − 1.
void SplitCholesky::Half::read_last_block() {
    const int s = size() - interior;
    last_block.setZero(s, s);
    for_each_lower_entry(*factor, interior, [&](int row, int column, double value) {
        last_block(row - interior, column - interior) = value;
    });
}

void SplitCholesky::Half::forward(const Eigen::MatrixXd& B, Eigen::Index first, int columns,
                                  std::vector<double>& z) const {
    z.assign(static_cast<std::size_t>(columns) * rows.size(), 0.0);
    for (int k = 0; k < interior; ++k) {
        const int row = rows[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
        for (int c = 0; c < columns; ++c) {
            z[static_cast<std::size_t>(columns * k + c)] = B(row, first + c);
        }
    }
    lower_solve(*factor, z.data(), columns);
}

void SplitCholesky::Half::push_separator(const std::vector<double>& z, int columns,
                                         Eigen::MatrixXd& rhs) const {
    const double* q = z.data() + static_cast<std::ptrdiff_t>(columns) * interior;
    for (Eigen::Index i = 0; i < last_block.rows(); ++i) {
        for (int c = 0; c < columns; ++c) {
            double sum = 0;
            for (Eigen::Index j = 0; j <= i; ++j) {
                sum += last_block(i, j) * q[columns * j + c];
            }
            rhs(separator_slot[static_cast<std::size_t>(i)], c) += sum;
        }
    }
}

void SplitCholesky::Half::backward(const Eigen::MatrixXd& x_s, std::vector<double>& z,
                                   Eigen::Index first, Eigen::MatrixXd& X) const {
    const auto columns = static_cast<int>(x_s.cols());
    double* lifted = z.data() + static_cast<std::ptrdiff_t>(columns) * interior;
    for (Eigen::Index j = 0; j < last_block.cols(); ++j) {
        for (int c = 0; c < columns; ++c) {
            double sum = 0;
            for (Eigen::Index i = j; i < last_block.rows(); ++i) {
                sum += last_block(i, j) * x_s(separator_slot[static_cast<std::size_t>(i)], c);
            }
            lifted[columns * j + c] = sum;
        }
    }
    upper_solve(*factor, z.data(), columns);
    for (int k = 0; k < interior; ++k) {
        const int row = rows[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
        for (int c = 0; c < columns; ++c) {
            X(row, first + c) = z[static_cast<std::size_t>(columns * k + c)];
        }
    }
}

SplitCholesky::SplitCholesky() = default;
SplitCholesky::~SplitCholesky() = default;

bool SplitCholesky::analyze(const Eigen::SparseMatrix<double>& A, double supernodal_switch) {
    const auto n = static_cast<std::size_t>(A.rows());
    cholmod_common common{};
    cholmod_start(&common);
    common.print = 0;
    cholmod_sparse pattern = Eigen::viewAsCholmod(A);
    pattern.stype = 1;  // symmetric: its upper triangle is read
    std::vector<int> part(n);
    const auto cut = cholmod_bisect(&pattern, nullptr, 0, 1, part.data(), &common);
    cholmod_finish(&common);
    if (cut < 0) {
        return false;
    }
    separator_.clear();
    std::vector<int> slot(n, -1);
    for (std::size_t r = 0; r < n; ++r) {
        if (part[r] == kCut) {
            slot[r] = static_cast<int>(separator_.size());
            separator_.push_back(static_cast<int>(r));
        }
    }
    for (int h = 0; h < 2; ++h) {
        auto half = std::make_unique<Half>();
        std::vector<int> local(n, -1);
        for (std::size_t r = 0; r < n; ++r) {
            if (part[r] == h) {
                local[r] = static_cast<int>(half->rows.size());
                half->rows.push_back(static_cast<int>(r));
            }
        }
        half->interior = static_cast<int>(half->rows.size());
        if (half->interior == 0) {
            return false;
        }
        for (const int r : separator_) {
            local[static_cast<std::size_t>(r)] = half->interior + slot[static_cast<std::size_t>(r)];
            half->rows.push_back(r);
        }
        half->gather_places(A, local);
        halves_[static_cast<std::size_t>(h)] = std::move(half);
    }
    bool analysed[2] = {false, false};
    for_both_halves([&](int h) {
        analysed[h] = halves_[static_cast<std::size_t>(h)]->analyze(supernodal_switch);
    });
    separator_entries_.clear();
    for (const int c : separator_) {
        for (Eigen::Index k = A.outerIndexPtr()[c]; k < A.outerIndexPtr()[c + 1]; ++k) {
            const int r = slot[static_cast<std::size_t>(A.innerIndexPtr()[k])];
            if (r >= 0) {
                separator_entries_.push_back(
                    {r, slot[static_cast<std::size_t>(c)], static_cast<int>(k)});
            }
        }
    }
    return analysed[0] && analysed[1] && pays_for_separator();
}

// The dense work on S, about s³ flops a factorization (s³/3 to factor the Schur complement,
// 2s³/3 to multiply out both halves' L_S L_Sᵀ), runs on one thread after the halves: it must
// stay below the smaller half's work for the halves side by side to save time. A surface mesh's
// separator is small (89 rows of the 43K armadillo, 179 of the 48K horse), a dense matrix's not.
bool SplitCholesky::pays_for_separator() const {
    const double s = static_cast<double>(separator_.size());
    return s * s * s <= std::min(halves_[0]->common.fl, halves_[1]->common.fl);
}

bool SplitCholesky::widen_supernodes() {
    bool widened[2] = {false, false};
    for_both_halves(
        [&](int h) { widened[h] = halves_[static_cast<std::size_t>(h)]->widen_supernodes(); });
    return widened[0] && widened[1];
}

bool SplitCholesky::factorize(const Eigen::SparseMatrix<double>& A,
                              const std::function<void()>& task) {
    bool factored[2] = {false, false};
    const int lighter = halves_[0]->common.fl <= halves_[1]->common.fl ? 0 : 1;
    std::exception_ptr task_failure;
    const auto factor_half = [&](int h) {
        factored[h] = halves_[static_cast<std::size_t>(h)]->factorize(A);
        if (h == lighter && task) {
            try {  // an exception may not leave the halves' OpenMP region
                task();
            } catch (...) {
                task_failure = std::current_exception();
            }
        }
    };
    // A simplicial factorization opens no region, and a team already running starts sooner than
    // a new thread.
    if (supernodal()) {
        for_both_halves_on_own_threads(factor_half);
    } else {
        for_both_halves(factor_half);
    }
    if (task_failure) {
        std::rethrow_exception(task_failure);
    }
    if (!factored[0] || !factored[1]) {
        return false;
    }
    assemble_schur_complement(A);
    return schur_.info() == Eigen::Success;
}

// A_SS − Σ_i A_Si A_ii⁻¹ A_iS = Σ_i L_Si L_Siᵀ − A_SS: each half's last block L_Si is the factor
// of its own Schur complement A_SS − A_Si A_ii⁻¹ A_iS.
void SplitCholesky::assemble_schur_complement(const Eigen::SparseMatrix<double>& A) {
    const auto s = static_cast<Eigen::Index>(separator_.size());
    Eigen::MatrixXd schur = Eigen::MatrixXd::Zero(s, s);
    for (const auto& [r, c, k] : separator_entries_) {
        schur(r, c) = -A.valuePtr()[k];
    }
    for (const auto& half : halves_) {
        const Eigen::MatrixXd product =
            half->last_block.triangularView<Eigen::Lower>() * half->last_block.transpose();
        for (Eigen::Index j = 0; j < s; ++j) {
            for (Eigen::Index i = 0; i < s; ++i) {
                schur(half->separator_slot[static_cast<std::size_t>(i)],
                      half->separator_slot[static_cast<std::size_t>(j)]) += product(i, j);
            }
        }
    }
    schur_.compute(schur);
}

Eigen::MatrixXd SplitCholesky::solve(const Eigen::MatrixXd& B) const {
    Eigen::MatrixXd X(B.rows(), B.cols());
    for (Eigen::Index first = 0; first < B.cols(); first += kFactorSolveColumns) {
        const auto columns =
            static_cast<int>(std::min<Eigen::Index>(kFactorSolveColumns, B.cols() - first));
        solve_columns(B, first, columns, X);
    }
    return X;
}

// Columns first … first + columns − 1 of X = A⁻¹ B. In each half's order, L = [L_I 0; L_SI L_S]:
// L⁻¹ of [b_I; 0] gives [L_I⁻¹ b_I; q] with L_S q = −A_SI A_II⁻¹ b_I, so the separator's rows
// solve (Schur) x_S = b_S + Σ L_S q; then L⁻ᵀ of [L_I⁻¹ b_I; L_Sᵀ x_S] gives [x_I; x_S].
void SplitCholesky::solve_columns(const Eigen::MatrixXd& B, Eigen::Index first, int columns,
                                  Eigen::MatrixXd& X) const {
    const auto s = static_cast<Eigen::Index>(separator_.size());
    std::array<std::vector<double>, 2> z;
    for_both_halves([&](int h) {
        halves_[static_cast<std::size_t>(h)]->forward(B, first, columns,
                                                      z[static_cast<std::size_t>(h)]);
    });
    Eigen::MatrixXd x_s(s, columns);
    for (Eigen::Index t = 0; t < s; ++t) {
        x_s.row(t) = B.row(separator_[static_cast<std::size_t>(t)]).segment(first, columns);
    }
    for (int h = 0; h < 2; ++h) {
        halves_[static_cast<std::size_t>(h)]->push_separator(z[static_cast<std::size_t>(h)],
                                                             columns, x_s);
    }
    for (int c = 0; c < columns; ++c) {  // column by column: the bits of each alone
        x_s.col(c) = schur_.solve(x_s.col(c));
    }
    for_both_halves([&](int h) {
        halves_[static_cast<std::size_t>(h)]->backward(x_s, z[static_cast<std::size_t>(h)], first,
                                                       X);
    });
    for (Eigen::Index t = 0; t < s; ++t) {
        X.row(separator_[static_cast<std::size_t>(t)]).segment(first, columns) = x_s.row(t);
    }
}

double SplitCholesky::factor_flops() const {
    return halves_[0]->common.fl + halves_[1]->common.fl;
}

double SplitCholesky::factor_entries() const {
    return halves_[0]->common.lnz + halves_[1]->common.lnz;
}

bool SplitCholesky::supernodal() const {
    return std::any_of(halves_.begin(), halves_.end(), [](const std::unique_ptr<Half>& half) {
        return half && half->factor != nullptr && half->factor->is_super != 0;
    });
}

}  // namespace genflow::detail

#endif
