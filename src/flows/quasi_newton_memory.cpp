// SPDX-License-Identifier: MIT
#include "flows/quasi_newton_memory.h"

#include <cmath>
#include <vector>

namespace genflow::detail {

namespace {

double dot(const VertexField& a, const VertexField& b) {
    return (a.array() * b.array()).sum();
}

}  // namespace

void QuasiNewtonMemory::record(const VertexField& positions, const VertexField& differential,
                               const Metric& metric) {
    if (last_positions_.rows() == positions.rows() && last_positions_.size() > 0) {
        VertexField s = positions - last_positions_;
        VertexField y = differential - last_differential_;
        const double curvature = dot(s, y);
        if (std::isfinite(curvature) && curvature > 0) {
            const double metric_y = dot(y, metric.gradient(y));  // yᵀG⁻¹y > 0 for SPD G
            if (std::isfinite(metric_y) && metric_y > 0) {
                scale_ = curvature / metric_y;
                pairs_.push_back({std::move(s), std::move(y), 1 / curvature});
                if (static_cast<int>(pairs_.size()) > capacity_) {
                    pairs_.pop_front();
                }
            }
        }
    }
    last_positions_ = positions;
    last_differential_ = differential;
}

VertexField QuasiNewtonMemory::direction(const VertexField& differential,
                                         const Metric& metric) const {
    if (pairs_.empty()) {
        return metric.gradient(differential);
    }
    VertexField q = differential;
    std::vector<double> alpha(pairs_.size());
    for (std::size_t k = pairs_.size(); k-- > 0;) {  // newest first
        alpha[k] = pairs_[k].rho * dot(pairs_[k].s, q);
        q -= alpha[k] * pairs_[k].y;
    }
    VertexField r = scale_ * metric.gradient(q);
    for (std::size_t k = 0; k < pairs_.size(); ++k) {  // oldest first
        const double beta = pairs_[k].rho * dot(pairs_[k].y, r);
        r += (alpha[k] - beta) * pairs_[k].s;
    }
    return r;
}

}  // namespace genflow::detail
