// SPDX-License-Identifier: MIT
#include "numerics/spd_solver.h"

#include <atomic>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "numerics/split_cholesky.h"
#include "numerics/supernodal_solve.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#ifdef GENFLOW_HAS_CHOLMOD
#include <Eigen/CholmodSupport>
#else
#include <Eigen/SparseCholesky>
#endif

namespace genflow::detail {

#ifdef GENFLOW_HAS_CHOLMOD
// Below this many rows the factorization is simplicial, above it as CHOLMOD decides.
constexpr Eigen::Index kSimplicialRows = 60000;
// Factorization::ByFlopDensity: supernodal from this many flops per entry of the factor.
// CHOLMOD's own switch (40) counts on a BLAS that is efficient on small blocks. Where system
// calls are cheap, simplicial was faster up to 71 and supernodal from 102; where they are dear
// (every one of CHOLMOD's OpenMP regions, several a supernode, makes one), simplicial is as
// fast or faster at every density measured, up to 153. The switch, just below 102, takes on
// each side the kind whose worst case over both machines is the smaller: between 71 and 102
// supernodal gains little where calls are cheap and takes about twice as long where they are dear
// (the 43K armadillo's larger half, at 83), above it gains up to 2.5 times and loses at most 1.4
// (docs/benchmarks.md, "By flop density", "Dear system calls").
constexpr double kSupernodalFlopDensity = 100;
#endif

namespace {

#ifdef GENFLOW_HAS_CHOLMOD
// Eigen's CHOLMOD LLᵀ, telling which kind of factor it holds.
class CholmodSolver
    : public Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower> {
public:
    [[nodiscard]] bool supernodal() const {
        return m_cholmodFactor != nullptr && m_cholmodFactor->is_super != 0;
    }
    [[nodiscard]] const cholmod_factor* factor() const { return m_cholmodFactor; }

    // Factors A, both of whose triangles are stored, from the one CHOLMOD permutes with a
    // single transpose: the upper one for a supernodal factor, which reading the lower one
    // transposes twice (about 1 ms of the horse's 50; docs/benchmarks.md, "The stiffness
    // pattern and the factor's triangle"), the lower one for a simplicial factor. The same bits
    // for a symmetric A.
    void factorize_either_triangle(const Eigen::SparseMatrix<double>& A) {
        if (!supernodal()) {
            factorize(A);
            return;
        }
        cholmod_sparse upper = Eigen::viewAsCholmod(A);
        upper.stype = 1;
        cholmod_factorize_p(&upper, m_shiftOffset, nullptr, 0, m_cholmodFactor, &cholmod());
        m_info =
            m_cholmodFactor->minor == m_cholmodFactor->n ? Eigen::Success : Eigen::NumericalIssue;
        m_factorizationIsOk = true;
    }
};

void numeric_factorization(CholmodSolver& solver, const Eigen::SparseMatrix<double>& A) {
    solver.factorize_either_triangle(A);
}
#else
void numeric_factorization(Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower>& solver,
                           const Eigen::SparseMatrix<double>& A) {
    solver.factorize(A);
}
#endif

// The numeric factorization, with CHOLMOD's own OpenMP regions held to one thread. Debian's
// CHOLMOD opens a region of a fixed four threads for each large supernode (copying and zeroing
// its columns, memory-bound work), whatever the thread count asked for; on two cores those
// teams cost more than they save: on the 173K armadillo a supernodal factorization takes 217
// instead of 341 ms with them held to one thread, the BLAS keeping its own threads
// (docs/benchmarks.md, "Against the anchors"). The same bits either way. A host `teams` region
// of one thread sets that limit; it may not be nested in a parallel region, where CHOLMOD's
// regions run on the calling thread anyway (one active level, OpenMP's default).
template <class Solver>
void factorize(Solver& solver, const Eigen::SparseMatrix<double>& A) {
#ifdef _OPENMP
    if (!omp_in_parallel()) {
#pragma omp teams num_teams(1) thread_limit(1)
        numeric_factorization(solver, A);
        return;
    }
#endif
    numeric_factorization(solver, A);
}

#ifdef GENFLOW_HAS_CHOLMOD
// Chooses between simplicial and supernodal LLᵀ before an analysis.
void set_mode(CholmodSolver& solver, Factorization factorization, Eigen::Index rows) {
    switch (factorization) {
        case Factorization::Supernodal:
            solver.setMode(Eigen::CholmodSupernodalLLt);
            return;
        case Factorization::ByFlopDensity:
        case Factorization::ByFlopDensityWide:
            // CHOLMOD's own choice with our switch; a simplicial factor is made LLᵀ, as the
            // other modes make it.
            solver.setMode(Eigen::CholmodAuto);
            solver.cholmod().supernodal_switch = kSupernodalFlopDensity;
            solver.cholmod().final_asis = 0;
            solver.cholmod().final_ll = 1;
            return;
        case Factorization::BySize:
            // CHOLMOD chooses the supernodal factorization by its flop count alone, but that
            // one hands many small blocks to the BLAS, whose threads then contend with the
            // flows run side by side. Simplicial is faster on whole matches up to 52K rows,
            // supernodal from 84K (docs/benchmarks.md, "Sparse factorization").
            solver.setMode(rows < kSimplicialRows ? Eigen::CholmodSimplicialLLt
                                                  : Eigen::CholmodAuto);
            return;
    }
}
#endif

}  // namespace

struct SpdSolver::Impl {
#ifdef GENFLOW_HAS_CHOLMOD
    CholmodSolver solver;  // LLᵀ, simplicial or supernodal (set_mode())
    // The factorization in two halves, if A is analysed for it (Factorization::ByFlopDensity)
    // and splits; else `solver` holds A's factor.
    std::unique_ptr<SplitCholesky> split;
    // Whether the split factor was analysed again with wider supernodes, how many times the
    // current pattern was factored, and how many columns its last factor solved.
    bool wide = false;
    int factorizations = 0;
    std::atomic<Eigen::Index> solved_columns{0};
#else
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> solver;
#endif
    Eigen::Index rows = -1;
    std::vector<Eigen::SparseMatrix<double>::StorageIndex> outer;
    std::vector<Eigen::SparseMatrix<double>::StorageIndex> inner;
    bool factored = false;

    void analyze(const Eigen::SparseMatrix<double>& A,
                 [[maybe_unused]] Factorization factorization) {
#ifdef GENFLOW_HAS_CHOLMOD
        split.reset();
        wide = false;
        factorizations = 0;
        // A flow that has the machine to itself factors in two halves side by side where A
        // splits: five fairing steps on the noisy tori of the cost curve take 0.77×, 0.79×,
        // 0.80× and 0.73× the time at 1K, 10K, 50K and 200K vertices (docs/benchmarks.md,
        // "Two halves").
        if (factorization == Factorization::ByFlopDensity ||
            factorization == Factorization::ByFlopDensityWide) {
            split = std::make_unique<SplitCholesky>();
            if (split->analyze(A, kSupernodalFlopDensity)) {
                // Wide from the first analysis where the use is known to want it: on the
                // horse, ten fairing steps take 0.90 times as long as when the second
                // factorization widens them (one factorization of the narrow kind, one
                // analysis and a factor's memory fewer).
                if (factorization == Factorization::ByFlopDensityWide && split->supernodal()) {
                    wide = split->widen_supernodes();
                }
                return;
            }
            split.reset();
        }
        set_mode(solver, factorization, A.rows());
#endif
        solver.analyzePattern(A);
    }

    // Whether A's numeric factorization succeeded; `task` runs alongside it (compute()).
    bool factorize(const Eigen::SparseMatrix<double>& A, const std::function<void()>& task) {
#ifdef GENFLOW_HAS_CHOLMOD
        if (split) {
            widen_for_few_solves();
            ++factorizations;
            solved_columns = 0;
            return split->factorize(A, task);
        }
#endif
        detail::factorize(solver, A);
        if (task) {
            task();
        }
        return solver.info() == Eigen::Success;
    }

#ifdef GENFLOW_HAS_CHOLMOD
    // Wider supernodes make a factorization faster and its solves slower, so a split factor is
    // widened, at its second factorization, when its first one's solves did less arithmetic
    // than the factorization (4 flops an entry of the factor and a column: forward and back):
    // a fairing step's one solve, a volume-controlled step's six (0.88 times the time of ten
    // steps on the horse), but not a frozen metric's, factored once and solved every step
    // (docs/benchmarks.md, "Two halves", "Dear system calls").
    void widen_for_few_solves() {
        if (factorizations != 1 || wide || solved_columns == 0) {
            return;
        }
        const double solve_flops =
            4 * split->factor_entries() * static_cast<double>(solved_columns.load());
        if (solve_flops < split->factor_flops()) {
            wide = split->widen_supernodes();
        }
    }
#endif

    bool same_pattern(const Eigen::SparseMatrix<double>& A) const {
        return A.rows() == rows && static_cast<std::size_t>(A.nonZeros()) == inner.size() &&
               std::equal(outer.begin(), outer.end(), A.outerIndexPtr()) &&
               std::equal(inner.begin(), inner.end(), A.innerIndexPtr());
    }
};

SpdSolver::SpdSolver(Factorization factorization)
    : impl_(std::make_unique<Impl>()), factorization_(factorization) {
#ifdef GENFLOW_HAS_CHOLMOD
    // A failure is reported as a SolverError; CHOLMOD printing its own warning as well would
    // add a second line to the tool's one-line message.
    impl_->solver.cholmod().print = 0;
#endif
}
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

void SpdSolver::compute(const Eigen::SparseMatrix<double>& A, const char* caller,
                        const std::function<void()>& task) {
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
    // A compressed A is read in place: a copy of the 48K horse's matrix cost a millisecond.
    Eigen::SparseMatrix<double> copy;
    if (!A.isCompressed()) {
        copy = A;
        copy.makeCompressed();
    }
    const Eigen::SparseMatrix<double>& compressed = A.isCompressed() ? A : copy;
    if (!impl_->same_pattern(compressed)) {
        impl_->analyze(compressed, factorization_);
        impl_->rows = compressed.rows();
        impl_->outer.assign(compressed.outerIndexPtr(),
                            compressed.outerIndexPtr() + compressed.outerSize() + 1);
        impl_->inner.assign(compressed.innerIndexPtr(),
                            compressed.innerIndexPtr() + compressed.nonZeros());
        ++analyses_;
    }
    impl_->factored = impl_->factorize(compressed, task);
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

bool SpdSolver::supernodal() const {
#ifdef GENFLOW_HAS_CHOLMOD
    if (impl_->split) {
        return impl_->factored && impl_->split->supernodal();
    }
    return impl_->factored && impl_->solver.supernodal();
#else
    return false;
#endif
}

bool SpdSolver::wide_supernodes() const {
#ifdef GENFLOW_HAS_CHOLMOD
    return impl_->wide;  // reset with the split at every analysis
#else
    return false;
#endif
}

bool SpdSolver::split() const {
#ifdef GENFLOW_HAS_CHOLMOD
    return impl_->factored && impl_->split != nullptr;
#else
    return false;
#endif
}

Eigen::MatrixXd SpdSolver::solve(const Eigen::MatrixXd& B) const {
    if (!impl_->factored || B.rows() != impl_->rows) {
        throw InvalidInput("SpdSolver::solve: no factorization of a matching size");
    }
    // Every column in one pass over the factor, 1.6× faster than one by one on the 48K horse's
    // three (docs/benchmarks.md, "Against the anchors"). A supernodal factor and a few columns
    // go to supernodal_solve(), whose rounding differs from CHOLMOD's by about 1e-16 of the
    // solution. Both it and the simplicial solve give each column the bits it gives alone.
#ifdef GENFLOW_HAS_CHOLMOD
    if (impl_->split) {
        impl_->solved_columns += B.cols();
        return impl_->split->solve(B);
    }
    const cholmod_factor* factor = impl_->solver.factor();
    if (factor != nullptr && fits_supernodal_solve(*factor, B.cols())) {
        return supernodal_solve(*factor, B);
    }
#endif
    return impl_->solver.solve(B);
}

}  // namespace genflow::detail
