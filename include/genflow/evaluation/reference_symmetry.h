// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <vector>

namespace genflow {

/// A reflection symmetry of a benchmark's reference points (a body's left–right symmetry): for
/// each reference point, the one at its mirror image. With it a map's error can also be taken
/// against the mirrored ground truth, and a map that put left for right shows as one whose
/// error is smaller there than against the ground truth itself.
struct ReferenceSymmetry {
    /// Per reference point, the reference point nearest its mirror image; empty if the set has
    /// no reflection symmetry within kSymmetryTolerance.
    std::vector<Eigen::Index> mirror;
    /// The shape it was read off (the one whose reference points are the most symmetric), and
    /// the root-mean-square distance there between each reflected point and its mirror, in
    /// units of that shape's √area.
    Eigen::Index shape = -1;
    double residual = 0;

    [[nodiscard]] bool found() const { return !mirror.empty(); }
};

/// Above this residual (√area units) the reference points have no mirror symmetry. A mirrored
/// map misplaces points by about the distance between the two sides (a body's width: 0.1–0.3
/// √area), so a symmetry this exact still tells a mirrored map from a right one; the FAUST
/// shapes' reference points in their most symmetric pose have 0.009.
inline constexpr double kSymmetryTolerance = 0.05;

/// Estimates the symmetry from the reference points' positions on every shape of a set
/// (`positions[s]`: row k is reference point k on shape s, every shape with the same rows;
/// `units[s]`: √area of shape s). On each shape a reflection plane is fitted by alternating
/// nearest mirrored points and the plane that best exchanges them (from each principal axis of
/// the points), on a fixed subsample of them; the shape with the smallest residual gives the
/// mirror of every reference point. Deterministic.
/// \throws InvalidInput if `positions` is empty, the shapes' row counts differ, there are fewer
///         than 4 reference points or `units` does not match.
[[nodiscard]] ReferenceSymmetry estimate_reference_symmetry(
    const std::vector<Eigen::MatrixX3d>& positions, const std::vector<double>& units);

}  // namespace genflow
