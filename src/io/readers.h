// SPDX-License-Identifier: MIT
// The per-format parsers behind read_mesh()/parse_mesh(). Each takes the whole file in memory.
#pragma once

#include <string_view>

#include "genflow/io/vertex_attributes.h"
#include "io/parse_context.h"

namespace genflow::detail {

/// With `attributes`, also the colours of `v x y z r g b` records (0–1), when every vertex has
/// one. Texture coordinates and normals (vt, vn) are not read, with a warning.
TriangleMesh parse_obj(std::string_view bytes, const ParseContext& context,
                       VertexAttributes* attributes = nullptr);
/// With `attributes`, also what the vertex element holds beside x, y, z: normals (nx, ny, nz or
/// normal_x, …), colours (red, green, blue or diffuse_red, …; 0–1 floats scaled to 0–255) and
/// every other single property as a named value, each with a row per vertex or none.
TriangleMesh parse_ply(std::string_view bytes, const ParseContext& context,
                       VertexAttributes* attributes = nullptr);
TriangleMesh parse_off(std::string_view bytes, const ParseContext& context);
TriangleMesh parse_stl(std::string_view bytes, const ParseContext& context);

/// A mesh file's bytes.
/// \throws IoError "<path>: <problem>" if it is a directory, cannot be opened or read, or is
///         empty.
std::string read_mesh_file(const std::filesystem::path& path);

}  // namespace genflow::detail
