// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "genflow/io/vertex_attributes.h"
#include "genflow/mesh.h"

namespace genflow {

/// How `write_mesh` encodes a PLY file.
enum class PlyEncoding { BinaryLittleEndian, Ascii };

/// How `write_mesh` stores coordinates in a PLY file.
enum class PlyPrecision {
    Double,  ///< `property double x`: positions round-trip exactly.
    Float    ///< `property float x`: half the size; what most scanners and viewers write.
};

/// Options of `write_mesh`. OBJ and OFF are always written as text with the shortest decimal
/// representation that reads back to the same double.
struct WriteMeshOptions {
    PlyEncoding ply_encoding = PlyEncoding::BinaryLittleEndian;
    PlyPrecision ply_precision = PlyPrecision::Double;
};

/// Writes `mesh` to `path` as OBJ, PLY, OFF, STL (binary, float) or binary glTF (.glb: float
/// positions, area-weighted vertex normals, a matte double-sided material, for web viewers and
/// Blender), chosen by the extension.
///
/// The write is atomic: the data goes to a temporary file in the same directory, which is
/// renamed over `path` only once everything was written and flushed. A failure never leaves a
/// partial file behind, and an existing file at `path` is kept unless the write succeeds.
///
/// \throws IoError      "<path>: <problem>" if the extension is not one of these, or the
///                      file cannot be written.
/// \throws InvalidInput if F holds an index outside V, or V a non-finite coordinate ("<path>:
///                      ..."; the file would be unreadable).
void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                const WriteMeshOptions& options = {});

/// Writes `mesh` with `attributes`: PLY keeps all of them (each scalar a vertex property in the
/// coordinates' type, colours as uchar red, green, blue, texture coordinates as texture_u,
/// texture_v or per corner as the faces' texcoord lists); glTF all but normals and texture
/// coordinates per corner (colours as COLOR_0, texture coordinates as TEXCOORD_0, each scalar
/// a float attribute "_NAME"); OBJ colours ("v x y z r g b", 0–1) and texture coordinates
/// (vt, per vertex or per corner); OFF colours (0–255), normals and texture coordinates per
/// vertex ("[ST][C][N]OFF"); STL none. What a format cannot hold is left out with a warning in
/// `warnings`, if given.
/// \throws as write_mesh() above, and InvalidInput for attributes that do not have a finite
///         row per vertex (texture coordinates per corner: a row of table indices per face),
///         or a scalar name with a space or one of x, y, z, red, green, blue.
void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                const VertexAttributes& attributes, const WriteMeshOptions& options = {},
                std::vector<std::string>* warnings = nullptr);

/// Whether write_mesh() writes the format `path`'s extension names (case-insensitive).
[[nodiscard]] bool is_writable_mesh_path(const std::filesystem::path& path);

}  // namespace genflow
