// SPDX-License-Identifier: MIT
#pragma once

#include <cstddef>
#include <memory>

#include "genflow/energies/energy.h"

namespace genflow {

/// How the vertex masses are turned into the weights a_i, b_j of the pseudo-Hausdorff sums.
enum class HausdorffWeights {
    Paper,      ///< a_i = m_i/P, b_j = m_j/Q (Appendix A)
    Normalized  ///< a_i = m_i/Σm, b_j = m_j/Σm: removes a mild (P, Q)-dependent factor
};

/// Parameters of the pseudo-Hausdorff distance.
struct PseudoHausdorffOptions {
    /// Exponent α ≥ 0.5: the larger, the closer d_H is to the (vertex-set) Hausdorff distance,
    /// and the stiffer the flow. Stable for any α up to several hundred (log-domain sums).
    double alpha = 8.0;
    /// Regularization ε > 0, a length: d_ij = |x_i − y_j|² + ε². For matching take about the
    /// target's mean edge length (docs/formulas.md §8: smaller values make the gradient snap
    /// vertices tangentially).
    double epsilon = 0.0;
    /// Truncation τ ∈ [0, 0.5): each f_i (and g_j) sums only over the target (source) points
    /// within an adaptive radius, chosen so that the neglected part of every sum is at most
    /// τ times the sum. Then the relative error of d_H + ε is at most τ/(2α(1 − τ)).
    /// The radius is the smaller of docs/formulas.md §8's (all weight assumed at the radius) and a
    /// shell bound from how much weight the grid holds around the point (fewer terms, the
    /// same guarantee).
    /// 0 evaluates the exact O(P·Q) sums.
    double truncation = 1e-4;
    HausdorffWeights weights = HausdorffWeights::Paper;
    /// Weight λ ∈ [0, 1] of the moving set's coverage term, S = λ Σ_i a_i/f_i + Σ_j b_j/g_j:
    /// 1 is the paper's symmetric distance. 0 asks only that every fixed point be near the
    /// moving set, so that moving points with no counterpart (a template's parts that a partial
    /// target does not show) are not pulled onto whatever is near; the f-sums are then not
    /// evaluated at all.
    double moving_coverage = 1.0;
};

/// Per-point descriptors that make d_H compare the points in R^{3+k}, (x_i, φ_i) against
/// (y_j, ψ_j): d_ij = |x_i − y_j|² + |φ_i − ψ_j|² + ε². A point is then near only to the points
/// that are both close and alike, so a descriptor that tells the parts of a shape apart (a heat
/// kernel signature: hands from hips) keeps a matching flow from fitting a part onto the wrong
/// one. The descriptors are lengths: scale them with the meshes. The moving mesh's stay with
/// its vertices (they do not change as X moves), so the differential keeps its form,
/// ∂d_H/∂x_i = Σ_j c_ij (x_i − y_j). No columns (the default) means no descriptors.
struct PointDescriptors {
    Eigen::MatrixXd moving;  ///< #P×k, one row per point of the moving set X
    Eigen::MatrixXd fixed;   ///< #Q×k, one row per point of the fixed set Y
};

/// Everything one evaluation produces; `value()`, `differential()` and `linearize()` share it.
struct PseudoHausdorffEvaluation {
    double value = 0;            ///< d_H(X, Y)
    VertexField differential;    ///< ∂d_H/∂X with frozen masses, #P×3
    Eigen::VectorXd coupling;    ///< Σ_j c_ij per source vertex (the diagonal of A in eq. 11)
    VertexField coupled_target;  ///< Σ_j c_ij y_j (so ∂d_H/∂x_i = coupling_i x_i − this)
    std::size_t pairs = 0;       ///< (i, j) terms evaluated, f and g sums together
};

/// d_H between point sets X (#P×3) and Y (#Q×3) with the given vertex masses (see
/// PseudoHausdorffEnergy for the formulas); the differential is with respect to X at fixed
/// masses. Points of zero mass take no part.
/// \throws InvalidInput for non-finite points, masses or descriptors, negative masses, a set
///         without a point of positive mass, mismatched sizes, or invalid options.
[[nodiscard]] PseudoHausdorffEvaluation pseudo_hausdorff(const Eigen::MatrixX3d& X,
                                                         const Eigen::VectorXd& mass_x,
                                                         const Eigen::MatrixX3d& Y,
                                                         const Eigen::VectorXd& mass_y,
                                                         const PseudoHausdorffOptions& options,
                                                         const PointDescriptors& descriptors = {});

/// The differentiable pseudo-Hausdorff distance of the paper's Appendix A (eq. 20) between the
/// moving mesh X (the argument of every call) and a fixed target Y (docs/formulas.md §8):
///
///     f_i = Σ_j b_j d_ij^{−α},   g_j = Σ_i a_i d_ij^{−α},   d_ij = |x_i − y_j|² + ε²
///     S = λ Σ_i a_i/f_i + Σ_j b_j/g_j,   d_H = S^{1/(2α)} − ε   (λ = 1 unless moving_coverage),
///
/// with a_i, b_j from the barycentric vertex masses (HausdorffWeights). Its differential is
/// ∂d_H/∂x_i = Σ_j c_ij (x_i − y_j), c_ij = S^{1/(2α)−1} a_i b_j d_ij^{−α−1}(λ f_i^{−2} +
/// g_j^{−2}), the paper's formula, which holds with the masses m^x frozen (they are recomputed at
/// every evaluation; docs/formulas.md §8 measures the omitted mass term at 3–6 % of the gradient
/// and keeps the frozen-mass descent direction). Its linearization is A = diag(Σ_j c_ij), B_i =
/// −Σ_j c_ij y_j, exact at X.
///
/// Sums run in the log domain (no overflow or underflow for α up to hundreds and any scale);
/// with truncation > 0 a uniform grid restricts them to near neighbours (as in the paper; the
/// target's grid is built once, the source's at every evaluation), and both cores are used
/// when OpenMP is available.
/// With PointDescriptors the distances are those of R^{3+k}; the truncation keeps its bound
/// (the radius comes from the full distances, the grid stays three-dimensional).
/// The last evaluation is cached, so value() then differential() at the same X cost one.
///
/// \note X and Y may have any sampling, connectivity, boundaries or components. Unreferenced
///       vertices (zero mass) take no part.
class PseudoHausdorffEnergy final : public Energy {
public:
    /// \throws InvalidInput if the target has no face, indexes outside its vertices or holds a
    ///         non-finite coordinate, or if α < 0.5, ε ≤ 0 or τ ∉ [0, 0.5).
    PseudoHausdorffEnergy(const TriangleMesh& target, const PseudoHausdorffOptions& options);
    /// With descriptors: `descriptors.fixed` has a row per target vertex, `descriptors.moving`
    /// a row per vertex of the meshes this energy is evaluated at.
    /// \throws InvalidInput as above, or if the descriptors are not finite, their column
    ///         counts differ or `fixed` does not have a row per target vertex.
    PseudoHausdorffEnergy(const TriangleMesh& target, const PseudoHausdorffOptions& options,
                          PointDescriptors descriptors);
    ~PseudoHausdorffEnergy() override;
    PseudoHausdorffEnergy(PseudoHausdorffEnergy&&) noexcept;
    PseudoHausdorffEnergy& operator=(PseudoHausdorffEnergy&&) noexcept;

    [[nodiscard]] double value(const TriangleMesh& mesh) const override;
    [[nodiscard]] VertexField differential(const TriangleMesh& mesh) const override;
    [[nodiscard]] std::optional<Linearization> linearize(const TriangleMesh& mesh) const override;

    /// One full evaluation at the positions of `mesh`.
    /// \throws InvalidInput if `mesh` has no face, bad indices or non-finite positions, or
    ///         (with descriptors) not as many vertices as `descriptors.moving` has rows.
    [[nodiscard]] PseudoHausdorffEvaluation evaluate(const TriangleMesh& mesh) const;

    [[nodiscard]] const PseudoHausdorffOptions& options() const { return options_; }

private:
    PseudoHausdorffOptions options_;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace genflow
