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
//
// The signatures cannot tell left from right, and neither can the map: on a figure whose left
// and right agree, ZoomOut may end near the mirrored map, and a match drawn towards it lies on
// the target inside out while its signatures agree better (TOSCA michael standing to kneeling,
// 2.65 → 4.59 % at the refined level, 65 % of its area facing away from the target). The
// turning functions tell (swapped_limbs.h): through such a fit their agreement with the
// target's falls below zero (michael 0.33 → −0.34). And a fit that sets right a match whose
// limbs lie around the wrong way may leave the signatures a little worse: the libigl elephant
// from rest to frame 300, 3.95 % off at the coarsest level, 1.39 % after its fit, against 3.62 %
// without (signatures +8.8 %, turning functions 0.40 → 0.78). So a fit is judged by both
// (keeps_fit()).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

#include "genflow/mesh.h"

namespace genflow::detail {

/// The smoothing length of a fit (fitted_to_map()) over the target's bounding-box diagonal.
inline constexpr double kMapFitLength = 0.01;

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

/// The share by which a fit after the first must lower the signatures' discrepancy, and the
/// first map's fit to be kept while it turns the turning functions worse (first_kept_fit()):
/// more than it changes between the successive maps of a converged fit (−2.0 … +4.6 % on the
/// 10 results measured, docs/eval/results.md).
inline constexpr double kMapFitProgress = 0.05;

/// How well a match agrees with its target intrinsically, before or after a fit.
struct FitRating {
    /// The heat kernel signatures' discrepancy (SpectralDescriptors::discrepancy()); lower is
    /// better.
    double discrepancy = 0;
    /// The turning functions' agreement (turning_agreement()): near 1 for a map that keeps every
    /// direction, below 0 for one that reverses most; 0 when it is not known.
    double turning = 0;
};

/// A right map's turning agreement (0.46–0.80 on 37 of the 45 h1 results of docs/eval, as
/// swapped_limbs.h's check measured it).
inline constexpr double kMapFitRightTurning = 0.4;
/// How much a fit must raise the turning agreement to be kept although the signatures agree
/// worse: more than fits that set nothing right move it. On the 67 h1 and articulated results
/// of docs/eval, the first fits the signatures kept changed it by −0.04 … +0.06 where nothing
/// large moved, and by +0.15 … +0.58 where whole limbs did; of those they refused, two raised
/// it to a right map's: the elephant's (+0.38; 3.62 → 1.39 %) and the libigl arm's from rest to
/// pose 3, articulated (+0.10; 1.16 → 0.98 %).
inline constexpr double kMapFitTurningGain = 0.08;
/// How much worse the signatures may then agree (as after an exchange of two limbs, which they
/// cannot tell either: −23 … +5 % on the three measured; the elephant's fit +8.8 %).
inline constexpr double kMapFitTurningDiscrepancy = 0.1;

/// Whether a fit that took a match rated `current` to one rated `fitted` is kept: never if it
/// leaves the turning agreement below both zero and where it was (the map it was drawn to is
/// mirrored); else if the signatures agree better by the share `progress` (0: at all), or if
/// the turning functions then agree as a right map's do, by kMapFitTurningGain more, with the
/// signatures at most kMapFitTurningDiscrepancy worse.
[[nodiscard]] bool keeps_fit(const FitRating& current, const FitRating& fitted, double progress);

/// Of fits of one match rated `current` to maps in the order of preference (kFineMapFirstSizes:
/// the map that may set whole limbs right first), the first that keeps_fit() keeps; none if it
/// keeps none. A later map is a fallback, not a rival: picking of two kept fits the one whose
/// signatures agree better changed 6 of 36 rows of docs/eval, 3 better by 0.04–0.10 % and 3
/// worse, the libigl arm articulated 1.89 → 3.28 % (its upper arm turned at once as far as the
/// later map puts it, and no further fit then did clearly better). A fallback is there to keep
/// the match's own left and right, so its fit is not kept either if it lowers the turning
/// agreement by more than kMapFitTurningGain (the MakeHuman body pose1→pose3, 0.76 → 0.62 with
/// the signatures 5 % better: 0.83 → 1.50 %; the twelve other fallbacks kept on docs/eval moved
/// it by −0.01 … +0.18). Nor is the first map's, unless its signatures agree better by more
/// than kMapFitProgress, the noise of converged fits: the libigl arm rest→pose 2 (h1, with the
/// step held after backtracking) went 0.44 → 0.23 with the signatures 0.4 % better, its
/// forearm twisted half a turn (14 % of its area turned over instead of 1.4 %), while the
/// MakeHuman hand's articulated match went 0.68 → 0.12 with them 41 % better, and right
/// (3.0 → 1.4 %): the turning functions of five fingers tell less than the signatures then.
[[nodiscard]] std::optional<std::size_t> first_kept_fit(const FitRating& current,
                                                        const std::vector<FitRating>& fitted,
                                                        double progress);

}  // namespace genflow::detail
