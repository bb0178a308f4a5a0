// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include "genflow/matching/match.h"
#include "genflow/mesh.h"
#include "genflow/spatial/closest_point.h"

namespace genflow {

/// For each row of `points` (#P×3), the closest point of `target`'s surface (face, barycentric
/// coordinates, point, distance): the correspondence of a deformed template to its target.
/// Uses both cores when OpenMP is available.
/// \throws InvalidInput as TriangleBvh, or if a point is not finite.
[[nodiscard]] std::vector<SurfacePoint> closest_points(const Eigen::MatrixX3d& points,
                                                       const TriangleMesh& target);

/// The correspondence of a match: per template vertex its counterpart on `target`
/// (MatchResult::counterparts) as a surface point, whose `distance` is how far from it the match
/// put the vertex. Without the counterparts' stage, closest_points() of the deformed template.
/// \throws InvalidInput if the result's counterparts and deformed template differ in rows.
[[nodiscard]] std::vector<SurfacePoint> match_correspondence(const MatchResult& result,
                                                             const TriangleMesh& target);

}  // namespace genflow
