// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/SparseCore>
#include <memory>
#include <utility>
#include <vector>

#include "genflow/metrics/metric.h"

namespace genflow {

/// Parameters of the quasi-isometric prior (paper §6.3.3, docs/formulas.md §7).
struct QuasiIsometricOptions {
    /// The rigidity length ℓ_iso as a fraction of the bounding-box diagonal: stretching a
    /// patch of size s costs about (ℓ_iso/s)² times as much as moving it, so shapes bend and
    /// articulate freely while patches smaller than ℓ_iso keep their edge lengths. λ_iso is
    /// ℓ_iso² (times diagonal²), which keeps its meaning at every resolution. Stiffer matches
    /// bends better (the generated limb bent by 35°: mean error 0.029, 0.028, 0.026, 0.024 of
    /// the diagonal at 0.05, 0.1, 0.2, 0.4), at more steps per level.
    double rigidity_length = 0.2;
    /// Extra "fake" edges across limbs (docs/formulas.md §7) for rigidity across a part's
    /// thickness, chosen once at the first update(); 0 = none.
    int fake_edges = 0;
    /// β: the weight of a fake edge relative to a mesh edge of the same length and mass.
    double fake_edge_weight = 1;
    /// Rebuild and refactor G at every `refresh_interval`-th update() only; in between, G of
    /// the last rebuild stays in force. Any SPD G gives a descent direction, so a flow still
    /// descends; 1 = the metric of docs/formulas.md §7 at every step.
    int refresh_interval = 1;
};

/// The quasi-isometric metric of docs/formulas.md §7: for fields U, V,
///
///     ⟨U, V⟩ = Σ_i m_i u_i·v_i + λ_iso Σ_e w_e [(u_i − u_j)·d_e][(v_i − v_j)·d_e],
///
/// d_e = x_i − x_j at the current positions and w_e = A_e/|d_e|⁴ (A_e a third of the areas of
/// the edge's faces), so the penalty is λ_iso Σ_e A_e (rate of strain along e)². G = M⊗I₃ + λK
/// couples the three coordinates (3n×3n, vertex i in rows 3i, 3i+1, 3i+2); K vanishes exactly
/// on rigid motions, so those cost only their L2 norm. G is sparse and factored by the sparse
/// Cholesky of genflow (symbolic analysis reused from step to step).
///
/// Fixed vertices are supported as by SparseMetric; the implicit step takes any symmetric PSD
/// #V×#V A (acting on each coordinate).
class QuasiIsometricMetric final : public Metric {
public:
    explicit QuasiIsometricMetric(const QuasiIsometricOptions& options = {});
    ~QuasiIsometricMetric() override;
    QuasiIsometricMetric(QuasiIsometricMetric&&) noexcept;
    QuasiIsometricMetric& operator=(QuasiIsometricMetric&&) noexcept;

    /// \throws InvalidInput as Metric::update(), or if the options are out of range
    ///         (rigidity_length and fake_edge_weight must be finite and non-negative,
    ///         fake_edges non-negative).
    void update(const TriangleMesh& mesh) override;
    [[nodiscard]] VertexField gradient(const VertexField& dEdX) const override;
    [[nodiscard]] VertexField apply(const VertexField& U) const override;
    [[nodiscard]] VertexField shifted_gradient(const Eigen::SparseMatrix<double>& A, double dt,
                                               const VertexField& R) override;

    /// G (3n×3n, interleaved coordinates) at the mesh last given to update(), without the
    /// fixed-vertex modification.
    [[nodiscard]] const Eigen::SparseMatrix<double>& matrix() const;

    /// The fake edges in use (vertex pairs), chosen at the first update() of a mesh with this
    /// vertex count.
    [[nodiscard]] const std::vector<std::pair<int, int>>& fake_edges() const;

private:
    QuasiIsometricOptions options_;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Pairs of vertices across the thickness of `mesh` (docs/formulas.md §7): for `count` vertices
/// spread by farthest-point sampling, a ray from the vertex along its inward normal, and the vertex
/// of the first face hit that lies nearest the hit. Vertices whose ray leaves the mesh are skipped,
/// so fewer pairs may come back; no pair repeats.
[[nodiscard]] std::vector<std::pair<int, int>> cross_limb_pairs(const TriangleMesh& mesh,
                                                                int count);

}  // namespace genflow
