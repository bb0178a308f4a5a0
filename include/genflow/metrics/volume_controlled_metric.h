// SPDX-License-Identifier: MIT
#pragma once

#include <memory>

#include "genflow/metrics/factorization.h"
#include "genflow/metrics/metric.h"

namespace genflow {

/// Parameters of the volume-controlled metric.
struct VolumeControlledOptions {
    /// Penalty λ ∈ (0, 1] on motions that change the volume locally. λ = 1 is the plain
    /// (lumped barycentric) L2 metric; as λ → 0 volume-changing motions are suppressed, and
    /// the volume lost by a flow is about λ times what the plain metric loses (docs/formulas.md
    /// §4).
    double lambda = 0.05;
    /// Relative tolerance of the iterative solves (CG for `apply()`, GMRES for the implicit
    /// step).
    double tolerance = 1e-10;
    /// How the preconditioner D + dt·A is factored.
    Factorization factorization = Factorization::BySize;
};

/// The volume-controlled metric of paper §5, in the corrected form of docs/formulas.md §4 (the
/// printed Π_VP is neither a projection nor self-adjoint and makes eq. 13 diverge).
///
/// With f = Nᵀv the normal speeds (unit area-weighted normals N), D the lumped barycentric
/// masses and the one-ring averaging Ψ_ij = [j ∈ N⁺(i)]/|N⁺(j)|, a = Ψm:
///
///     P = N Ψᵀ diag(1/a) Ψ D Nᵀ        (D-self-adjoint, spectrum in [0, 1])
///     B = L_VP⁻¹ = I − (1 − λ) P        (D-self-adjoint SPD, spectrum in [λ, 1])
///     G = D L_VP = D B⁻¹.
///
/// G is dense and never formed: `gradient()` is the cheap B D⁻¹ dE/dX, `apply()` solves with B
/// by conjugate gradients, and `shifted_gradient()` (the implicit step, eq. 13 made precise)
/// solves (G + dt·A) y = R through the n×n system of the normal speeds that B changes, by
/// GMRES(50) with one solve with the plain fairing matrix D + dt·A an iteration (one Cholesky
/// factorization per step; docs/formulas.md §4).
///
/// P does not depend on the sign of the normals, so inward-oriented meshes are handled alike.
/// \note Works on any mesh; vertices without a normal (isolated, degenerate) have no normal
///       speed and move as in L2.
class VolumeControlledMetric final : public Metric {
public:
    /// \throws InvalidInput unless 0 < λ ≤ 1 and the tolerance is in (0, 1).
    explicit VolumeControlledMetric(VolumeControlledOptions options = {});
    ~VolumeControlledMetric() override;
    VolumeControlledMetric(VolumeControlledMetric&&) noexcept;
    VolumeControlledMetric& operator=(VolumeControlledMetric&&) noexcept;

    void update(const TriangleMesh& mesh) override;
    [[nodiscard]] VertexField gradient(const VertexField& dEdX) const override;
    [[nodiscard]] VertexField apply(const VertexField& U) const override;
    [[nodiscard]] VertexField shifted_gradient(const Eigen::SparseMatrix<double>& A, double dt,
                                               const VertexField& R) override;

    /// P·v, the soft projection onto locally volume-changing motions (for tests and analysis).
    [[nodiscard]] VertexField volume_changing_part(const VertexField& v) const;

    /// GMRES iterations of the last `shifted_gradient()`.
    [[nodiscard]] int last_iterations() const;

    [[nodiscard]] const VolumeControlledOptions& options() const { return options_; }

private:
    VolumeControlledOptions options_;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace genflow
