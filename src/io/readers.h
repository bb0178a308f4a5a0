// SPDX-License-Identifier: MIT
// The per-format parsers behind read_mesh()/parse_mesh(). Each takes the whole file in memory.
#pragma once

#include <string_view>

#include "io/parse_context.h"

namespace genflow::detail {

TriangleMesh parse_obj(std::string_view bytes, const ParseContext& context);
/// With `vertex_normals`, also the vertices' normals where the vertex element has them (nx, ny,
/// nz or normal_x, normal_y, normal_z): #V×3, else no rows.
TriangleMesh parse_ply(std::string_view bytes, const ParseContext& context,
                       Eigen::MatrixX3d* vertex_normals = nullptr);
TriangleMesh parse_off(std::string_view bytes, const ParseContext& context);
TriangleMesh parse_stl(std::string_view bytes, const ParseContext& context);

/// A mesh file's bytes.
/// \throws IoError "<path>: <problem>" if it is a directory, cannot be opened or read, or is
///         empty.
std::string read_mesh_file(const std::filesystem::path& path);

}  // namespace genflow::detail
