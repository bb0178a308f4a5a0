// SPDX-License-Identifier: MIT
#pragma once

namespace genflow {

/// How a metric's sparse Cholesky factorizations are made with CHOLMOD (Eigen's fallback, in a
/// build without CHOLMOD, is always simplicial).
enum class Factorization {
    /// Simplicial below 60,000 rows, CHOLMOD's choice above: the choice the matcher's flows,
    /// which run side by side, were measured with.
    BySize,
    /// Supernodal at every size: the faster for a flow that has the machine to itself where
    /// system calls are cheap (on the 48K horse a factorization takes 48 instead of 103 ms;
    /// where they are dear 102 instead of 74; docs/benchmarks.md).
    Supernodal,
    /// Supernodal where the factorization does at least 100 flops per entry of the factor,
    /// simplicial below, for a flow that has the machine to itself: on either side, the kind
    /// whose worst case is the smaller on the machines measured (at 71 flops per entry, the 43K
    /// armadillo, a simplicial factorization and solve take 40 instead of 46 ms; at 102, a 40K
    /// range scan, 72 instead of 47 ms where system calls are cheap; docs/benchmarks.md, "By
    /// flop density" and "Dear system calls"). Where the matrix splits at a small vertex
    /// separator, its two halves are factored so, side by side on two threads, and the separator
    /// densely (docs/formulas.md §10): on the 48K horse 32 instead of 46 ms.
    ByFlopDensity,
    /// ByFlopDensity for a metric factored anew before each solve or few (a flow that updates
    /// it at every step, not a frozen one): supernodal halves get wider supernodes from the
    /// first analysis, which make a factorization faster and its solves slower (the horse's
    /// halves 31.5–33.1 → 25.3–25.8 ms, a three-column solve 4.4–4.6 → 6.8–7.0 ms).
    /// ByFlopDensity widens them at the second factorization when the first one's solves did
    /// less arithmetic than it; this spares that factorization of the narrow kind and the
    /// analysis again.
    ByFlopDensityWide,
};

}  // namespace genflow
