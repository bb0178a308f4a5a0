// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <vector>

#include "genflow/mesh.h"
#include "genflow/spatial/closest_point.h"

namespace genflow {

/// For each row of `points` (#P×3), the closest point of `target`'s surface (face, barycentric
/// coordinates, point, distance): the correspondence of a deformed template to its target.
/// Uses both cores when OpenMP is available.
/// \throws InvalidInput as TriangleBvh, or if a point is not finite.
[[nodiscard]] std::vector<SurfacePoint> closest_points(const Eigen::MatrixX3d& points,
                                                       const TriangleMesh& target);

/// Writes correspondences as text, atomically: a `#` header, then one line per template vertex
/// i (0-based, in order): `face b0 b1 b2 distance`, the target face and the barycentric
/// coordinates of the corresponding point on its corners F(face, 0..2), and the distance from
/// the deformed vertex to it.
/// \throws IoError if the file cannot be written.
void write_correspondences(const std::filesystem::path& path,
                           const std::vector<SurfacePoint>& correspondences);

}  // namespace genflow
