// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <vector>

#include "genflow/spatial/closest_point.h"

namespace genflow {

/// Writes correspondences as text, atomically (as write_mesh()): a `#` header, then one line
/// per template vertex i (0-based, in order): `face b0 b1 b2 distance`, the target face and the
/// barycentric coordinates of the corresponding point on its corners F(face, 0..2), and the
/// distance from the deformed vertex to it.
/// \throws IoError "<path>: <problem>" if the file cannot be written; nothing is left behind.
void write_correspondences(const std::filesystem::path& path,
                           const std::vector<SurfacePoint>& correspondences);

}  // namespace genflow
