// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "genflow/metrics/metric.h"
#include "genflow/operators/mass_matrix.h"

namespace genflow {

/// A block of deformation fields that a subspace metric treats alike (docs/formulas.md §6).
struct FieldBlock {
    /// 3n×m: column c is one field, the vector of vertex i in rows 3i, 3i+1, 3i+2.
    Eigen::MatrixXd fields;
    /// Penalty μ > 0 on motions in the block's span: the metric is μ times L2 there, so μ < 1
    /// makes them cheaper (the flow prefers them by 1/μ) and μ = 1 is neutral.
    double penalty = 1;
};

/// Builds the blocks, in priority order, at the current positions of `mesh`, with `masses`
/// the metric's lumped vertex masses (for centroids that match the inner product).
using FieldBasis =
    std::function<std::vector<FieldBlock>(const TriangleMesh& mesh, const Eigen::VectorXd& masses)>;

/// Parameters of the subspace metric.
struct SubspaceOptions {
    /// The lumped mass M of the underlying L2 inner product.
    MassType mass = MassType::Barycentric;
};

/// The prioritized subspace metric of docs/formulas.md §6, one mechanism for the quasi-rigid
/// (§6.3.1) and quasi-articulated (§6.3.2) priors: given blocks B_1, …, B_K with penalties μ_k,
/// block Gram–Schmidt in a base inner product B (the lumped mass M by default: the paper's L2)
/// gives B-orthonormal Q_k (each block minus what earlier blocks span; directions already spanned
/// are dropped), and
///
///     G = B + Σ_k (μ_k − 1) B Q_k Q_kᵀ B,   G⁻¹ dE = B⁻¹ dE + Σ_k (1/μ_k − 1) Q_k Q_kᵀ dE,
///
/// which is SPD for any μ_k > 0 (the paper's eqs. 17–19 are not; see docs/formulas.md §6): the
/// blocks' motions cost μ_k times their B-norm, the residual its B-norm. With B = M (L = I + Σ (μ_k
/// − 1) Q_k Q_kᵀ M) the residual is free to move each vertex alone, as L2 does; with a Sobolev base
/// (the `base` constructor argument, e.g. H1Metric) it moves smoothly. The blocks are rebuilt
/// from the current positions at every `update()`; applying G or G⁻¹ costs O(n·m) plus one
/// application of B or B⁻¹, the rebuild O(n·m²) plus m applications of B, for m fields in all:
/// one Gram matrix Fᵀ B F of all the fields F, on which the Gram–Schmidt runs (Q_k = F T_k).
///
/// The implicit step (`shifted_gradient`) supports a diagonal A (the pseudo-Hausdorff
/// linearization): G + dt·A = E + U Γ Uᵀ with E = B + dt·A, U = [B Q_k] and Γ = diag(μ_k − 1),
/// solved by the Woodbury identity (docs/formulas.md §9). With the default base E is diagonal; with
/// another, E is solved by its own shifted_gradient() once per non-neutral field plus once.
///
/// \note Fixed vertices are not supported (update() throws if a mask is set).
class SubspaceMetric final : public Metric {
public:
    /// `base`: the inner product B of the residual (updated with this metric); null for the
    /// lumped mass M of `options.mass`. The basis is given that lumped mass either way.
    explicit SubspaceMetric(FieldBasis basis, SubspaceOptions options = {},
                            std::unique_ptr<Metric> base = nullptr);

    /// \throws InvalidInput as Metric::update(), if a fixed-vertex mask is set, or if the basis
    ///         returns a block with the wrong row count, a non-finite entry or a penalty that
    ///         is not positive and finite.
    void update(const TriangleMesh& mesh) override;
    [[nodiscard]] VertexField gradient(const VertexField& dEdX) const override;
    [[nodiscard]] VertexField apply(const VertexField& U) const override;
    /// \throws InvalidInput additionally if A is not diagonal.
    [[nodiscard]] VertexField shifted_gradient(const Eigen::SparseMatrix<double>& A, double dt,
                                               const VertexField& R) override;

    /// The B-orthonormal blocks Q_k of the last update() (empty blocks dropped), with their
    /// penalties.
    [[nodiscard]] std::vector<FieldBlock> orthonormal_blocks() const;
    /// The lumped masses of the last update().
    [[nodiscard]] const Eigen::VectorXd& masses() const { return masses_; }

private:
    // B X for the 3n-row columns of X, and B⁻¹ x.
    [[nodiscard]] Eigen::MatrixXd base_times(const Eigen::MatrixXd& X) const;
    [[nodiscard]] Eigen::VectorXd base_inverse_times(const Eigen::VectorXd& x) const;

    FieldBasis basis_;
    SubspaceOptions options_;
    std::unique_ptr<Metric> base_;  // null: B = M
    Eigen::VectorXd masses_;
    Eigen::VectorXd row_masses_;  // m_i for each of the 3n rows
    // The fields of the last update() side by side, F (3n×m).
    Eigen::MatrixXd fields_;
    // Q_k = F T_k, B-orthonormal, and μ_k; T_k has a row for each column of F up to block
    // k's last (the rest of T_k is zero).
    struct CoefficientBlock {
        Eigen::MatrixXd T;
        double penalty;
    };
    std::vector<CoefficientBlock> coefficients_;
    Eigen::MatrixXd gradient_weights_;  // Σ (1/μ_k − 1) T_k T_kᵀ
    Eigen::MatrixXd apply_weights_;     // Σ (μ_k − 1) T_k T_kᵀ
};

/// Penalties of the quasi-rigid prior (paper §6.3.1): each in (0, 1], smaller = that motion is
/// cheaper. The defaults are docs/formulas.md §9's (a step is then almost entirely rigid plus
/// scaling).
struct QuasiRigidOptions {
    double translation = 5e-3;
    double rotation = 5e-3;
    double scaling = 5e-2;
    MassType mass = MassType::Barycentric;
};

/// The fields of rigid motion and scaling at the current positions: translations e_a,
/// rotations e_a × (x_i − c) and the scaling x_i − c about the M-centroid c (docs/formulas.md §5:
/// the blocks are M-orthogonal only for that centre), in blocks T, R, S with the given penalties.
[[nodiscard]] std::vector<FieldBlock> rigid_motion_blocks(const TriangleMesh& mesh,
                                                          const Eigen::VectorXd& masses,
                                                          const QuasiRigidOptions& options);

/// The quasi-rigid metric: a SubspaceMetric over rigid_motion_blocks() (paper eq. 16).
[[nodiscard]] SubspaceMetric quasi_rigid_metric(const QuasiRigidOptions& options = {});

}  // namespace genflow
