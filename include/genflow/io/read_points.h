// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace genflow {

/// Whether `path` names an XYZ point file (extension .xyz, case-insensitive).
[[nodiscard]] bool is_xyz_file(const std::filesystem::path& path);

/// A point cloud's points and, where its file gives them, their normals.
struct PointCloud {
    Eigen::MatrixX3d points;   ///< #P×3
    Eigen::MatrixX3d normals;  ///< #P×3, or no rows
};

/// Reads a point cloud: an XYZ file (one point per line, `x y z`, or `x y z nx ny nz` with its
/// normal on every line; further numbers are skipped; `#` starts a comment), or the vertices of
/// an OBJ, PLY, OFF or STL file (its faces, if it has any, are not read). A PLY file's vertex
/// normals are read where its vertex element has them (nx, ny, nz, or normal_x, normal_y,
/// normal_z as PCL writes them), as a scanner exports them; other formats' normals are not.
/// \param warnings  if given, receives the mesh reader's warnings.
/// \throws IoError "<path>: <problem>" (for XYZ "<path>: line N: <problem>") if the file cannot
///         be read, is malformed, holds a non-finite coordinate, a zero or non-finite normal,
///         no point, or normals on some lines only.
[[nodiscard]] PointCloud read_points(const std::filesystem::path& path,
                                     std::vector<std::string>* warnings = nullptr);

}  // namespace genflow
