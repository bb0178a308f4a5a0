// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace genflow {

/// Whether `path` names an XYZ point file (extension .xyz, case-insensitive).
[[nodiscard]] bool is_xyz_file(const std::filesystem::path& path);

/// Reads the points of a point cloud (#P×3): an XYZ file (one point per line, `x y z`,
/// optionally followed by more numbers such as a normal `nx ny nz`, which are not needed and
/// skipped; `#` starts a comment), or the vertices of an OBJ, PLY, OFF or STL file (its faces,
/// if it has any, are not read into the result).
/// \param warnings  if given, receives the mesh reader's warnings.
/// \throws IoError "<path>: <problem>" (for XYZ "<path>: line N: <problem>") if the file cannot
///         be read, is malformed, holds a non-finite coordinate or no point.
[[nodiscard]] Eigen::MatrixX3d read_points(const std::filesystem::path& path,
                                           std::vector<std::string>* warnings = nullptr);

}  // namespace genflow
