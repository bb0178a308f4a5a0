// SPDX-License-Identifier: MIT
// L-BFGS's memory of past steps, in a metric (Nocedal & Wright, Numerical Optimization, Alg. 7.4):
// the inverse Hessian is approximated from the last pairs s_k = X_{k+1} − X_k,
// y_k = dE(X_{k+1}) − dE(X_k), starting from the metric's own inverse G⁻¹ scaled by
// sᵀy / yᵀG⁻¹y. Without memory the direction is the metric's gradient, so the prior shapes every
// step as it does the steepest descent of eq. 14; the pairs add the energy's curvature along the
// way, which the steepest flow of d_H lacks and which is why it creeps.
#pragma once

#include <deque>

#include "genflow/mesh.h"
#include "genflow/metrics/metric.h"

namespace genflow::detail {

class QuasiNewtonMemory {
public:
    /// Keeps the last `capacity` pairs (≥ 1).
    explicit QuasiNewtonMemory(int capacity) : capacity_(capacity) {}

    /// Records the positions reached and their differential dE/dX; from the second call on, the
    /// step from the previous ones joins the memory. A step along which dE does not grow
    /// (sᵀy ≤ 0: d_H is not convex) would make the approximation indefinite and is dropped.
    void record(const VertexField& positions, const VertexField& differential,
                const Metric& metric);

    /// H dE/dX, H the approximate inverse Hessian (the two-loop recursion): the step is minus
    /// this. With an empty memory, the metric's gradient G⁻¹ dE/dX.
    [[nodiscard]] VertexField direction(const VertexField& differential,
                                        const Metric& metric) const;

    [[nodiscard]] bool empty() const { return pairs_.empty(); }

    /// Forgets every pair (the next direction is the metric's gradient); the last recorded
    /// positions stay the origin of the next step.
    void clear() { pairs_.clear(); }

private:
    struct Pair {
        VertexField s;
        VertexField y;
        double rho;  // 1 / sᵀy
    };

    int capacity_;
    std::deque<Pair> pairs_;
    double scale_ = 1;  // sᵀy / yᵀG⁻¹y of the newest pair: H₀ = scale_·G⁻¹
    VertexField last_positions_;
    VertexField last_differential_;
};

}  // namespace genflow::detail
