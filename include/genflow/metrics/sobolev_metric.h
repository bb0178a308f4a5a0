// SPDX-License-Identifier: MIT
#pragma once

#include <memory>

#include "genflow/metrics/sparse_metric.h"
#include "genflow/operators/mass_matrix.h"

namespace genflow {

/// Parameters of the Sobolev metrics.
struct SobolevOptions {
    /// Weight λ > 0 of the first-derivative term. It has units of area: the gradient is smoothed
    /// over a distance of roughly √λ, so scale it with the mesh (e.g. a multiple of the squared
    /// mean edge length).
    double lambda = 1.0;
    /// Weight μ ≥ 0 of the second-derivative term (units of length⁴); H2Metric only.
    double mu = 0.0;
    /// The outer mass matrix M. The Δ² term of H2 always uses the lumped barycentric D.
    MassType mass = MassType::Barycentric;
    /// How G is factored (Factorization::Supernodal for a flow that has the machine to itself).
    Factorization factorization = Factorization::BySize;
};

/// The Sobolev H1 metric <u, w> = ∫ u·w dA + λ ∫ ∇u·∇w dA (paper §4), i.e. L = Id − λΔ:
///
///     G = M + λ K,
///
/// with K the cotan stiffness matrix (`cotan_stiffness()`, symmetric PSD). Stepping along the
/// H1 gradient of the surface area with λ = dt is exactly implicit fairing
/// (M + dt K) X' = M X [Desbrun et al. 1999] (docs/formulas.md §2).
///
/// \note Works on any triangle mesh, with or without boundary, several components; degenerate
///       triangles get clamped cotangents and zero mass instead of NaN.
class H1Metric final : public SparseMetric {
public:
    /// \throws InvalidInput if `options.lambda` is not positive and finite.
    explicit H1Metric(SobolevOptions options = {});
    [[nodiscard]] const SobolevOptions& options() const { return options_; }

    ~H1Metric() override;
    H1Metric(H1Metric&&) noexcept;
    H1Metric& operator=(H1Metric&&) noexcept;

protected:
    [[nodiscard]] Eigen::SparseMatrix<double> assemble(const TriangleMesh& mesh) const override;

private:
    SobolevOptions options_;
    // The sparsity pattern of the last connectivity assembled (lumped masses only), reused
    // while the faces stay the same, as they do in a flow.
    struct PatternCache;
    std::unique_ptr<PatternCache> pattern_cache_;
};

/// The Sobolev H2 metric, L = Id − λΔ + μΔ² (paper §4, docs/formulas.md §3):
///
///     G = M + λ K + μ K D⁻¹ K,
///
/// with D the lumped barycentric mass (the inverse of the full mass matrix would be dense);
/// G has two-ring sparsity. For the area with λ = dt, one explicit step solves
/// (M + dt K + μ K D⁻¹ K) X' = (M + μ K D⁻¹ K) X (docs/formulas.md §3: this is not
/// Desbrun et al.'s higher-order fairing).
class H2Metric final : public SparseMetric {
public:
    /// \throws InvalidInput if λ is not positive and finite or μ is negative or not finite.
    explicit H2Metric(SobolevOptions options);
    [[nodiscard]] const SobolevOptions& options() const { return options_; }

protected:
    [[nodiscard]] Eigen::SparseMatrix<double> assemble(const TriangleMesh& mesh) const override;

private:
    SobolevOptions options_;
};

}  // namespace genflow
