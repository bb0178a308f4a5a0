// SPDX-License-Identifier: MIT
// How far a match is from the ground truth (issue 5's evaluation): per template vertex, the
// distance to where it belongs, and whether it was stranded on the wrong part of the shape; per
// face, whether it was turned over.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "genflow/mesh.h"

namespace genflow {

/// When a vertex counts as stranded (correspondence_error()). `length` is a fraction of the
/// ground truth's bounding-box diagonal and `detour` a ratio, so the defaults need no tuning per
/// mesh.
struct StrandedOptions {
    /// A vertex put within this distance of its ground truth, along the surface, is never
    /// stranded: a limb's reach, well above a finger's width, so that a finger put on its
    /// neighbour counts in the errors, not as stranded (docs/measurements.md, "Stranded
    /// vertices"). CorrespondenceError::reversed shows such parts.
    double length = 0.1;
    /// Farther than `length`, it is stranded when the path along the surface from its ground
    /// truth to where it was put is more than this many times the straight distance: it sits
    /// on a surface that is near in space but far on the shape (a finger on its neighbour, a
    /// hand on the hip). A vertex slid along its own limb, however far, has a path about as
    /// long as the straight line and counts in the errors only.
    double detour = 2;
    /// A vertex put within this many mean edge lengths of the ground truth from where it
    /// belongs is at its place and never stranded: where two parts of the ground truth touch
    /// (a fingertip on the next finger, the thighs), a vertex a fraction of an edge from its
    /// own place may be nearer the other part, which the sampling cannot tell from its own.
    double placement_tolerance = 1;
};

/// The error of a deformed template against the ground truth (same vertex count and order:
/// vertex i of `truth` is where template vertex i belongs).
struct CorrespondenceError {
    /// |x_i − g_i| over the diagonal of `truth`'s bounding box, per template vertex.
    Eigen::VectorXd distance;
    /// Per template vertex: whether it is stranded (StrandedOptions).
    std::vector<bool> stranded;
    /// Per face of `truth`: whether the match turned it over (its normal makes more than 90°
    /// with its normal in the ground truth). A part put back to front near its own place, such
    /// as a hand palm for back, stays within `StrandedOptions::length` of where it belongs and
    /// a few percent of the diagonal off on average: its faces show it.
    std::vector<bool> reversed;
    double mean = 0;
    double median = 0;
    double max = 0;
    Eigen::Index stranded_count = 0;
    Eigen::Index reversed_count = 0;
    /// The reversed faces' share of the ground truth's area, in [0, 1].
    double reversed_area = 0;
};

/// Measures `deformed` (#V×3, the template's vertices after a match) against `truth`. A vertex
/// not at its place (StrandedOptions::placement_tolerance) is placed on the ground-truth
/// surface point nearest to it; its path from g_i is walked over the chords between vertices
/// of `truth` at most two edges apart (to a corner of the face reached, then straight), which
/// follows the surface closely even on long thin triangles, where paths along the edges
/// zigzag. Each vertex is decided by the bounds that 32 landmark vertices give on path lengths
/// where they suffice, else by an A* search towards the face that stops at the bound that
/// decides; a match gone wrong takes about as long as a good one.
/// Faces are compared by their normals in `deformed` and in `truth` (`truth`'s faces index
/// both). Uses both cores when OpenMP is available.
/// \throws InvalidInput if the vertex counts differ, a point is not finite, `truth` has no face
///         or a zero diagonal, or the options are not finite, with length > 0, detour ≥ 1 and
///         placement_tolerance ≥ 0.
[[nodiscard]] CorrespondenceError correspondence_error(const Eigen::MatrixX3d& deformed,
                                                       const TriangleMesh& truth,
                                                       const StrandedOptions& options = {});

}  // namespace genflow
