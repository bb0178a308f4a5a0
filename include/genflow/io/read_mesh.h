// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "genflow/io/mesh_format.h"
#include "genflow/io/vertex_attributes.h"
#include "genflow/mesh.h"

namespace genflow {

/// Reads a triangle mesh from an OBJ, PLY (ascii, binary little or big endian), OFF or STL
/// (ascii or binary) file; the format is chosen by the extension.
///
/// - Polygons with more than three corners are split into a fan of triangles around their first
///   corner, and a warning says how many were split. Faces with fewer than three corners are
///   dropped with a warning.
/// - STL stores a triangle soup: vertices with bitwise-equal coordinates are merged, in order of
///   first appearance.
/// - With `attributes`, a PLY file's vertex normals, colours, texture coordinates and other
///   vertex properties and its faces' `texcoord` lists are read into it (VertexAttributes;
///   genflow writes them back), and so are an OBJ file's `v x y z r g b` colours, `vt` texture
///   coordinates and `vn` normals. Texture coordinates are kept per vertex where no seam gives
///   a vertex two, else per corner; normals only per vertex. Everything else (normals that
///   differ at a vertex's corners, materials, other PLY elements) is skipped, with a warning
///   where it held data.
/// - Nothing is checked beyond what is needed to parse the file: call `validate()` on the result
///   for non-finite coordinates, indices out of range, degenerate or non-manifold faces.
///
/// The readers are our own and are fuzzed: a malformed or truncated file raises IoError, it
/// never crashes, hangs or allocates more than the file's size can justify.
///
/// \param warnings  if given, receives one line per recoverable oddity of the file.
/// \throws IoError  "<path>: <problem>" if the file cannot be opened, its extension is unknown,
///                  or its content is malformed.
[[nodiscard]] TriangleMesh read_mesh(const std::filesystem::path& path,
                                     std::vector<std::string>* warnings = nullptr,
                                     VertexAttributes* attributes = nullptr);

/// Parses a mesh held in memory; the same as `read_mesh` without the file. `source_name`
/// prefixes the messages of thrown IoErrors and warnings.
[[nodiscard]] TriangleMesh parse_mesh(std::string_view bytes, MeshFormat format,
                                      std::string_view source_name = "<memory>",
                                      std::vector<std::string>* warnings = nullptr,
                                      VertexAttributes* attributes = nullptr);

}  // namespace genflow
