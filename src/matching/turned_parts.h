// SPDX-License-Identifier: MIT
// Parts a match put back to front in their own place, and turning them back.
//
// A cylinder's turn about its axis costs d_H nothing, so an extremity the coarse levels placed
// turned (TOSCA michael's hands palm for back, 164° and 171°, with h1) stays turned: every
// finer level keeps it, and nothing extrinsic tells (d_H after a flow was even a little lower
// with the hands wrong). A functional map does tell, once it has enough eigenfunctions to see
// a thumb: ZoomOut to 60 functions from the match's own correspondence puts michael's hands
// within 0.7 % of the ground truth, where the match is 2.9 % off. It is not right everywhere
// (it flips the head, which is nearly symmetric, left for right), so it is only believed where
// it disputes the match over a whole part, by a turn of more than 90°, without reflecting it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "genflow/mesh.h"
#include "matching/fine_spectrum.h"

namespace genflow::detail {

/// One part of the template that the map places turned against the match.
struct TurnedPart {
    /// Where the map disputes the match by this one turn (refitted to the vertices it explains:
    /// a hand's turn, not the partial one of the forearm it blends into).
    std::vector<Eigen::Index> vertices;
    Eigen::RowVector3d from_centre;  ///< their centroid as the match placed them
    Eigen::RowVector3d to_centre;    ///< and as the map places them
    Eigen::AngleAxisd turn;          ///< the rotation between the two, about the centroids
    /// The whole connected part the map disputes, and where it puts those vertices (rows as
    /// `region`): the turn is blended over it.
    std::vector<Eigen::Index> region;
    Eigen::MatrixX3d region_mapped;
};

struct TurnedPartOptions {
    /// A vertex is disputed when the map puts it this far from the match, over the target's
    /// bounding-box diagonal.
    double disputed_distance = 0.015;
    /// Parts smaller than the map resolves, 1/functions of the template's area (60 functions
    /// tell about 60 regions apart), are left alone: on the wolf, the horse and the small
    /// centaur the map turned paws and hooves of 0.3–1.4 % of the area in place, wrongly (the
    /// mean error rose 0.55 → 0.72 % on the wolf); michael's hands are 2.0 and 2.2 %.
    /// Only parts turned by more than this (radians) are turned back.
    double min_angle = 1.5707963267948966;
    /// A part whose map is fitted this much better by a reflection than by a rotation (root
    /// mean square residuals, from the template at rest) is mirrored by the map: left alone.
    double reflection_ratio = 0.8;
};

/// The parts of `deformed` (the template's vertices as a match placed them; `template_rest` the
/// same template at rest, for its connectivity) that `map`, the functional map from the
/// template to `target` (FineSpectrum::zoomed_out_map(), 60 functions, from this match),
/// places turned, largest first.
/// \throws InvalidInput if `deformed` or `map` does not have the template's vertex count.
[[nodiscard]] std::vector<TurnedPart> find_turned_parts(const TriangleMesh& template_rest,
                                                        const Eigen::MatrixX3d& deformed,
                                                        const TriangleMesh& target,
                                                        const VertexMap& map,
                                                        const TurnedPartOptions& options = {});

/// `deformed` with each part turned back as the map places it, and the rest of its region by
/// a share of the same turn: per vertex the share that takes it nearest to where the map puts
/// it, smoothed over the region (1 on the part, 0 outside). A limb's twist thus fades along
/// it as the map says, and nothing outside the region moves (a turn about the forearm would
/// swing the upper arm). Measured on michael: a share fading linearly with the distance from
/// the hand left the forearm twisted 92° at that level, and the result 0.50 % off with a
/// Hausdorff distance of 1.8 %; fitted to the map, 0.44 % and 1.5 %.
[[nodiscard]] Eigen::MatrixX3d turned_back(const TriangleMesh& template_rest,
                                           const Eigen::MatrixX3d& deformed,
                                           const std::vector<TurnedPart>& parts);

}  // namespace genflow::detail
