// SPDX-License-Identifier: MIT
// A match drawn towards where a fine functional map puts it.
//
// The flow of d_H settles a part wherever the target's surface is near, so a limb may end a
// little along or around the right one. A functional map of many eigenfunctions, refined by
// ZoomOut from the match's own correspondence, knows intrinsically where each part belongs, but
// it lands each vertex on a target vertex, is noisy from vertex to vertex and may put a few
// vertices on a far part of the target. So the match is drawn towards it by a smooth (H1) step,
// only where the map does not tear such pieces off, and flows again.
//
// Whether a fit helped is told intrinsically, by two measures (keeps_fit()): the heat kernel
// signatures (SpectralDescriptors::discrepancy()), which see where parts belong, and the
// turning functions (swapped_limbs.h), which see left from right, to which the signatures and
// the map are blind. What each rule was measured on: docs/measurements.md, "Fits to the fine
// map".
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
/// put on a far part of the target, such as a tail on the back) are not trusted.
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
/// more than it changes between the successive maps of a converged fit (−2.0 … +4.6 %
/// measured, docs/measurements.md).
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

/// A right map's turning agreement: right maps measure 0.46–0.80, maps with limbs on their
/// mirror images well below.
inline constexpr double kMapFitRightTurning = 0.4;
/// How much a fit must raise the turning agreement to be kept although the signatures agree
/// worse: more than fits that set nothing right move it (−0.04 … +0.06 measured), less than fits
/// that move whole limbs do (+0.15 … +0.58).
inline constexpr double kMapFitTurningGain = 0.08;
/// How much worse the signatures may then agree: they cannot tell left from right, so a fit
/// that sets a limb's side right may leave them a little worse.
inline constexpr double kMapFitTurningDiscrepancy = 0.1;

/// Whether a fit that took a match rated `current` to one rated `fitted` is kept: never if it
/// leaves the turning agreement below both zero and where it was (the map it was drawn to is
/// mirrored); else if the signatures agree better by the share `progress` (0: at all), or if
/// the turning functions then agree as a right map's do, by kMapFitTurningGain more, with the
/// signatures at most kMapFitTurningDiscrepancy worse.
[[nodiscard]] bool keeps_fit(const FitRating& current, const FitRating& fitted, double progress);

/// Of fits of one match rated `current` to maps in the order of preference (kFineMapFirstSizes:
/// the map that may set whole limbs right first), the first that keeps_fit() keeps; none if it
/// keeps none. A later map is a fallback, not a rival: choosing between two kept fits by their
/// signatures moves whole parts as far as the later map puts them at once. A fallback is there
/// to keep the match's own left and right, so its fit is not kept either if it lowers the
/// turning agreement by more than kMapFitTurningGain. Nor is the first map's, unless its
/// signatures agree better by more than kMapFitProgress, the noise of converged fits: a small
/// gain of the signatures can come with a limb twisted half a turn.
[[nodiscard]] std::optional<std::size_t> first_kept_fit(const FitRating& current,
                                                        const std::vector<FitRating>& fitted,
                                                        double progress);

}  // namespace genflow::detail
