// SPDX-License-Identifier: MIT
#pragma once

namespace genflow {

/// How a metric's sparse Cholesky factorizations are made with CHOLMOD (Eigen's fallback, in a
/// build without CHOLMOD, is always simplicial).
enum class Factorization {
    /// Simplicial below 60,000 rows, CHOLMOD's choice above: the choice the matcher's flows,
    /// which run side by side, were measured with.
    BySize,
    /// Supernodal at every size: the faster for a flow that has the machine to itself (on the
    /// 48K horse a factorization takes 48 instead of 103 ms; docs/benchmarks.md).
    Supernodal,
    /// Supernodal where the factorization does at least 80 flops per entry of the factor,
    /// simplicial below: the faster of the two, on either side, for a flow that has the machine
    /// to itself (at 71 flops per entry, the 43K armadillo, a simplicial factorization and solve
    /// take 40 instead of 46 ms; at 102, a 40K range scan, 72 instead of 47 ms;
    /// docs/benchmarks.md, "By flop density"). Where the matrix splits at a small vertex
    /// separator, its two halves are factored so, side by side on two threads, and the separator
    /// densely (docs/formulas.md §10): on the 48K horse 32 instead of 46 ms.
    ByFlopDensity,
};

}  // namespace genflow
