// SPDX-License-Identifier: MIT
// A match drawn towards where a fine functional map puts it.
//
// The flow of d_H settles a part wherever the target's surface is near, so a limb may end a
// little along or around the right one (the makehuman hand's fingers: 1.94 % mean error with
// h1, 3.09 % with the articulated prior). A functional map of 60 eigenfunctions, refined by
// ZoomOut from the match's own correspondence, knows intrinsically where each part belongs;
// but it lands each vertex on a target vertex, is noisy from vertex to vertex and may put a
// few vertices on a far part of the target. So the match is drawn towards it by a smooth (H1)
// step, only where the map does not tear such pieces off, and flows again; whether that helped
// is told intrinsically, by the heat kernel signatures (SpectralDescriptors::discrepancy()).
// Measured over the 43 h1 and articulated results of docs/eval (the fit forced on each): the
// signatures agreed better on 20, and the fit was better on 18 of those (hand 1.94 → 1.29 %,
// FAUST 000→003 articulated 3.25 → 1.31 %), 0.02 and 0.03 worse on two; they agreed worse
// wherever the fit did real harm (the makehuman body 0.54 → 2.29 %, its map being coarser
// than the match; TOSCA michael kneeling 3.49 → 7.34 %, where the match is wrong over whole
// parts and ZoomOut ends near a wrong map).
#pragma once

#include <Eigen/Core>

#include "genflow/mesh.h"

namespace genflow::detail {

/// Where a map tears: the two ends of an edge put more than this times (its length at the
/// match + the target's mean edge length) apart.
inline constexpr double kMapTear = 3;

/// Per vertex of `deformed` (the template as matched), 1 where `placement` (#V×3, where a map
/// puts each vertex) may be trusted, else 0. A map that is right is continuous up to the
/// target's sampling; where it tears, the pieces smaller than `min_area` (a few vertices it
/// put on a far part of the target: a TOSCA cat's tail on its back) are not trusted.
/// \throws InvalidInput if `placement` does not have the mesh's vertex count.
[[nodiscard]] Eigen::VectorXd trusted_vertices(const TriangleMesh& deformed,
                                               const Eigen::MatrixX3d& placement,
                                               double target_edge, double min_area);

/// `deformed` moved towards `placement` by one step of the H1 flow of ½‖X − P‖²_{WM}:
///
///     X + (W M + λ K)⁻¹ W M (P − X),   λ = length²,
///
/// with M (barycentric) and K those of `deformed` and W the per-vertex `weights` (empty: all
/// 1): the map's per-vertex noise is smoothed over about `length`, parts it places elsewhere
/// move there whole, and vertices of weight 0 follow their neighbours.
/// \throws InvalidInput if `placement` or non-empty `weights` do not have the mesh's vertex
///         count or `length` is not positive and finite.
[[nodiscard]] Eigen::MatrixX3d fitted_to_map(const TriangleMesh& deformed,
                                             const Eigen::MatrixX3d& placement, double length,
                                             const Eigen::VectorXd& weights = {});

}  // namespace genflow::detail
