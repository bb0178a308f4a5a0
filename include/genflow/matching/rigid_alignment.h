// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <vector>

#include "genflow/mesh.h"

namespace genflow {

/// A similarity transform x ↦ s·R·x + t (R a rotation, s > 0).
struct Similarity {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    double scale = 1;

    /// The transform applied to every row of `points` (#P×3).
    [[nodiscard]] Eigen::MatrixX3d apply(const Eigen::MatrixX3d& points) const;
    /// As a 4×4 homogeneous matrix.
    [[nodiscard]] Eigen::Matrix4d matrix() const;
};

/// Parameters of align_rigidly(). The defaults need no tuning per mesh: every length is taken
/// from the meshes.
struct RigidAlignmentOptions {
    /// Each mesh is reduced to about this many area-weighted points (voxel clusters).
    int samples = 150;
    /// Iterations of the rigid flow for every one of the 24 starts, then for the best few
    /// distinct ones (rotations at least 30° apart).
    int start_iterations = 10;
    int best_starts = 6;
    int refine_iterations = 100;
    /// A flow stops when d_H fell by less than this fraction over 10 iterations.
    double stagnation_tolerance = 1e-3;
    /// Exponent of the pseudo-Hausdorff distance that is minimised. Low: a rigid fit between
    /// poses should follow the bulk of the shape, not the limbs that moved (with α = 8 the right
    /// orientation ranked lower; docs/measurements.md, "Rigid starts").
    double alpha = 2;
    /// Allow a uniform scaling, s = √(area of fixed / area of moving): area, unlike size or
    /// principal radii, does not change with the pose of a near-isometric shape.
    bool allow_scaling = true;
    /// Weight in [0, 1] of the moving mesh's coverage term in d_H
    /// (PseudoHausdorffOptions::moving_coverage): 0 for a fixed mesh that shows only part of the
    /// moving one, which then need not be near it everywhere.
    double moving_coverage = 1;
};

/// What align_rigidly() found.
struct RigidAlignment {
    Similarity transform;     ///< maps `moving` onto `fixed`
    double hausdorff_energy;  ///< d_H between the aligned samples
};

/// Aligns `moving` to `fixed` up to a rotation, translation and (optionally) scaling, without
/// correspondences and from any initial pose (issue 5's global initialization): both meshes are
/// reduced to area-weighted samples; the 24 rotations that map the principal axes of one onto
/// those of the other (every axis order and sign, determinant +1) are each followed by a short
/// rigid flow of the pseudo-Hausdorff distance (steepest descent in the M-weighted rigid
/// subspace, applied as finite rotations, Armijo backtracking); the best few are refined and
/// the lowest d_H wins. Principal axes are only starting points, so shapes whose axes change
/// with the pose (a cat stretching) are still aligned.
///
/// The lowest d_H is not always the right pose: between strongly articulated poses a rigid fit
/// can prefer a flipped orientation (half the d_H of the right one, measured).
/// rigid_alignment_candidates() therefore returns the distinct optima, so that a non-rigid flow
/// can decide; align_rigidly() returns the first.
///
/// \throws InvalidInput if a mesh has no face, zero area, bad indices or non-finite
///         coordinates, or the options are out of range (samples < 8, iterations < 0,
///         best_starts < 1, alpha < 0.5).
[[nodiscard]] std::vector<RigidAlignment> rigid_alignment_candidates(
    const TriangleMesh& moving, const TriangleMesh& fixed,
    const RigidAlignmentOptions& options = {});

/// The best of rigid_alignment_candidates().
[[nodiscard]] RigidAlignment align_rigidly(const TriangleMesh& moving, const TriangleMesh& fixed,
                                           const RigidAlignmentOptions& options = {});

}  // namespace genflow
