// SPDX-License-Identifier: MIT
#pragma once

#include "genflow/mesh.h"
#include "genflow/metrics/subspace_metric.h"
#include "genflow/parts/part_model.h"

namespace genflow {

/// Parameters of the quasi-articulated prior. Penalties are in (0, 1]: the smaller, the
/// cheaper that motion.
struct QuasiArticulatedOptions {
    /// Penalty of the global rigid motion (translation, rotation; scaling at 10× this).
    double global = 5e-3;
    /// Penalty of the rotations of the parts one level below the root; each deeper level's is
    /// 10× larger (docs/formulas.md §6: the boosts 1/μ decrease ×10 per level), at most `deepest`.
    double first_level = 1e-2;
    double deepest = 0.5;
    /// Hard labels are blended over about this many mean edge lengths around each seam
    /// (docs/formulas.md §6: W = (D + r²K)⁻¹ D χ, r ≥ 2–3 edge lengths); soft weights are used as
    /// given.
    double blend_edges = 3;
    /// The residual (the motion no part's rotation spans) is measured in H1 with λ = (k·h)²,
    /// k = smoothing_length and h the rest template's mean edge length, so that it moves
    /// smoothly (SubspaceMetric's base); 0 measures it in L2, as the paper does. Not used by
    /// the matcher: longer lengths matched rigged pairs worse (docs/measurements.md,
    /// "Articulated prior").
    double smoothing_length = 0;
    MassType mass = MassType::Barycentric;
};

/// Part weights blended across seams: W = (D + r²K)⁻¹ D χ column by column (D lumped mass,
/// K cotan stiffness, r = blend_edges × mean edge length), clipped to [0, 1], rows normalized.
/// Rows of χ that are already soft (not a single 1) are kept as they are.
/// \throws InvalidInput if the sizes disagree; SolverError if the system cannot be factored.
[[nodiscard]] Eigen::MatrixXd blend_part_weights(const TriangleMesh& mesh,
                                                 const Eigen::MatrixXd& weights,
                                                 double blend_edges);

/// The quasi-articulated metric of docs/formulas.md §6 ("kinematic" basis): a SubspaceMetric whose
/// blocks are, in priority order, the global rigid motion, then for each level of the part
/// tree the rotations W̃_k(i)·e_a × (x_i − c_k) of every part k at that level about its joint
/// c_k, where W̃_k is the blended weight of the subtree hanging at k (a linearized linear-blend
/// skinning: when a part turns, its children follow). The joint centres move with the mesh:
/// each is bound at construction to a fixed affine combination of the template vertices of its
/// seam (weighted by W̃(1 − W̃)), plus the constant offset to the given rest centre.
///
/// `rest` is the template (at the positions the part model's joint centres refer to).
/// \throws InvalidInput if the model does not fit the mesh (check_part_model()) or an option
///         is out of range.
[[nodiscard]] SubspaceMetric quasi_articulated_metric(const TriangleMesh& rest,
                                                      const PartModel& parts,
                                                      const QuasiArticulatedOptions& options = {});

}  // namespace genflow
