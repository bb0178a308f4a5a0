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
};

}  // namespace genflow
