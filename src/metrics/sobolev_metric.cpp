// SPDX-License-Identifier: MIT
#include "genflow/metrics/sobolev_metric.h"

#include <cmath>

#include "genflow/exceptions.h"
#include "genflow/operators/cotan_stiffness.h"
#include "metrics/metric_support.h"
#include "operators/stiffness_pattern.h"
#include "operators/triangle.h"

namespace genflow {

struct H1Metric::PatternCache : detail::StiffnessPatternCache {};

H1Metric::H1Metric(SobolevOptions options)
    : SparseMetric(options.factorization),
      options_(options),
      pattern_cache_(std::make_unique<PatternCache>()) {
    if (!detail::finite_above(options_.lambda, 0)) {
        throw InvalidInput("H1Metric: lambda must be positive and finite, got " +
                           std::to_string(options_.lambda));
    }
}

H1Metric::~H1Metric() = default;
H1Metric::H1Metric(H1Metric&&) noexcept = default;
H1Metric& H1Metric::operator=(H1Metric&&) noexcept = default;

Eigen::SparseMatrix<double> H1Metric::assemble(const TriangleMesh& mesh) const {
    if (options_.mass == MassType::Full || !pattern_cache_) {  // !pattern_cache_: moved from
        return detail::floored_mass_matrix(mesh, options_.mass) +
               options_.lambda * cotan_stiffness(mesh);
    }
    // The same matrix to the bit (StiffnessPattern), without sorting its entries again.
    return pattern_cache_->diagonal_plus_stiffness(
        mesh, detail::floored_lumped_masses(mesh, options_.mass), options_.lambda, CotanOptions{},
        "H1Metric");
}

H2Metric::H2Metric(SobolevOptions options)
    : SparseMetric(options.factorization), options_(options) {
    if (!detail::finite_above(options_.lambda, 0)) {
        throw InvalidInput("H2Metric: lambda must be positive and finite, got " +
                           std::to_string(options_.lambda));
    }
    if (!detail::finite_at_least(options_.mu, 0)) {
        throw InvalidInput("H2Metric: mu must be non-negative and finite, got " +
                           std::to_string(options_.mu));
    }
}

Eigen::SparseMatrix<double> H2Metric::assemble(const TriangleMesh& mesh) const {
    const Eigen::SparseMatrix<double> K = cotan_stiffness(mesh);
    const Eigen::VectorXd d = detail::floored_lumped_masses(mesh, MassType::Barycentric);
    const Eigen::SparseMatrix<double> KDinvK = K * d.cwiseInverse().asDiagonal() * K;
    return detail::floored_mass_matrix(mesh, options_.mass) + options_.lambda * K +
           options_.mu * KDinvK;
}

}  // namespace genflow
