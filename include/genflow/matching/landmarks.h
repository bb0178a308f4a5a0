// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "genflow/matching/rigid_alignment.h"
#include "genflow/mesh.h"

namespace genflow {

/// A correspondence the user knows: template vertex `vertex` goes to `target_point`, a point in
/// the target's frame (on or near its surface).
struct Landmark {
    Eigen::Index vertex = 0;
    Eigen::Vector3d target_point = Eigen::Vector3d::Zero();
    /// Its share of the landmarks' term relative to the others' (positive): a landmark weighs
    /// weight / Σ weights of it.
    double weight = 1;
};

/// Landmarks of a match (MatchOptions::landmarks): soft constraints in every level's flow, and
/// the judge of the rigid starts (docs/matching.md, "Landmarks").
struct LandmarkOptions {
    /// None: a match without landmarks.
    std::vector<Landmark> points;
    /// The landmarks' term beside d_H: this times the target's diagonal D times their mean
    /// squared distance in units of D (LandmarkEnergy); at 1, landmarks a diagonal off weigh as
    /// d_H of surfaces a diagonal apart. The prior moves a landmark's vertex with the region
    /// around it, whose d_H resists as a whole, so the default is ten times that: the
    /// landmarks end near their points (docs/matching.md, "Landmarks").
    double weight = 10;
    /// Onto a partial target (whose match runs without the intrinsic stages), spread three or
    /// more landmarks into a dense map of it, one landmark more for each vertex the coarsest
    /// level has on the part shown, by the points' geodesic distances to the landmarks
    /// (docs/matching.md, "Landmarks onto a partial target"): between a few landmarks the
    /// template slides on a view, and nothing else holds it. The given landmarks keep their
    /// term; the spread ones add one of four times its weight.
    bool spread_onto_partial = true;
};

/// The landmarks' mean squared distance from `positions` (the template's vertices, placed) to
/// their points, each weighted by its Landmark::weight.
[[nodiscard]] double landmark_mean_squared_distance(const std::vector<Landmark>& landmarks,
                                                    const Eigen::MatrixX3d& positions);

/// The similarity (rotation, translation and uniform scale) that takes the landmarks' template
/// vertices nearest to their points in the least-squares sense, each weighted by its
/// Landmark::weight (Umeyama 1991), or nothing with fewer than three landmarks or all of them on
/// one line, which leave a rotation free.
[[nodiscard]] std::optional<Similarity> landmark_similarity(
    const std::vector<Landmark>& landmarks, const Eigen::MatrixX3d& template_vertices);

}  // namespace genflow
