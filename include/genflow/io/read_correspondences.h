// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <vector>

#include "genflow/mesh.h"
#include "genflow/spatial/closest_point.h"

namespace genflow {

/// Reads the correspondences write_correspondences() writes (`genflow match --correspondence`):
/// after `#` lines, one line per template vertex, `face b0 b1 b2 distance`. Each becomes the
/// point of `target`'s face `face` at those barycentric coordinates.
/// \throws IoError "<path>: line N: <problem>" for a line of another shape, a face outside
///         `target`, barycentric coordinates that are not finite, below −1e-6 or do not sum to 1
///         within 1e-6, or a distance that is negative or not finite; "<path>: ..." if the file
///         cannot be read or has another number of lines than `template_vertices`.
[[nodiscard]] std::vector<SurfacePoint> read_correspondences(const std::filesystem::path& path,
                                                             const TriangleMesh& target,
                                                             Eigen::Index template_vertices);

}  // namespace genflow
