// SPDX-License-Identifier: MIT
// Parts a match put back to front in their own place, and turning them back.
//
// A cylinder's turn about its axis costs d_H nothing, so an extremity the coarse levels placed
// turned (a hand palm for back) stays turned: every finer level keeps it, and nothing
// extrinsic tells. A functional map does tell, once it has enough eigenfunctions to see a
// thumb. It is not right everywhere (it may flip a nearly symmetric head left for right), so it
// is only believed where it disputes the match over a whole part, by a turn of more than 90°,
// without reflecting it. Measurements: docs/measurements.md, "Turned parts".
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
    /// tell about 60 regions apart), are left alone: the map turns smaller paws and hooves in
    /// place wrongly.
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
/// swing the upper arm); a share fading linearly with the distance from the part left the limb
/// next to it twisted.
[[nodiscard]] Eigen::MatrixX3d turned_back(const TriangleMesh& template_rest,
                                           const Eigen::MatrixX3d& deformed,
                                           const std::vector<TurnedPart>& parts);

}  // namespace genflow::detail
