// SPDX-License-Identifier: MIT
#pragma once

#include "genflow/metrics/sparse_metric.h"
#include "genflow/operators/mass_matrix.h"

namespace genflow {

/// Parameters of the L2 metric.
struct L2Options {
    /// The mass matrix M. Lumped types make the gradient a division by vertex areas.
    MassType mass = MassType::Barycentric;
};

/// The L2 metric <u, w> = ∫ u·w dA (paper eq. 4), G = M: the inner product almost every mesh
/// flow uses without saying so. The L2 gradient of the area is the mean-curvature normal.
///
/// \note Works on any mesh; vertex masses (the diagonal of M) are floored at 1e-10 × their mean
///       so that isolated or fully degenerate vertices, whose differentials vanish, do not make
///       G singular.
class L2Metric final : public SparseMetric {
public:
    explicit L2Metric(L2Options options = {}) : options_(options) {}
    [[nodiscard]] const L2Options& options() const { return options_; }

protected:
    [[nodiscard]] Eigen::SparseMatrix<double> assemble(const TriangleMesh& mesh) const override;

private:
    L2Options options_;
};

}  // namespace genflow
