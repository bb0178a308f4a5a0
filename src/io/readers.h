// SPDX-License-Identifier: MIT
// The per-format parsers behind read_mesh()/parse_mesh(). Each takes the whole file in memory.
#pragma once

#include <string_view>

#include "genflow/io/vertex_attributes.h"
#include "io/parse_context.h"

namespace genflow::detail {

/// With `attributes`, also the colours of `v x y z r g b` records (0–1), when every vertex has
/// one, the texture coordinates of `vt` records (per vertex where no seam gives a vertex two,
/// else per corner) and the normals of `vn` records (when each vertex has one), when every face
/// names them; what is left out is warned about.
TriangleMesh parse_obj(std::string_view bytes, const ParseContext& context,
                       VertexAttributes* attributes = nullptr);
/// With `attributes`, also what the vertex element holds beside x, y, z: normals (nx, ny, nz or
/// normal_x, …), colours (red, green, blue or diffuse_red, …; 0–1 floats scaled to 0–255),
/// texture coordinates (u, v; s, t; texture_u, texture_v) and every other single property as a
/// named value, each with a row per vertex or none; and the face element's `texcoord` lists
/// (per vertex where no seam gives a vertex two, else per corner).
TriangleMesh parse_ply(std::string_view bytes, const ParseContext& context,
                       VertexAttributes* attributes = nullptr);
/// With `attributes`, also the vertex columns the keyword announces: normals (N), colours (C;
/// integers 0–255 or fractions 0–1, alpha dropped) and texture coordinates (ST); face colours
/// are left out with a warning.
TriangleMesh parse_off(std::string_view bytes, const ParseContext& context,
                       VertexAttributes* attributes = nullptr);
TriangleMesh parse_stl(std::string_view bytes, const ParseContext& context);

/// A mesh file's bytes.
/// \throws IoError "<path>: <problem>" if it is a directory, cannot be opened or read, or is
///         empty.
std::string read_mesh_file(const std::filesystem::path& path);

}  // namespace genflow::detail
