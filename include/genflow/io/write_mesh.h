// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>

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

/// Writes `mesh` to `path` as OBJ, PLY or OFF, chosen by the extension.
///
/// The write is atomic: the data goes to a temporary file in the same directory, which is
/// renamed over `path` only once everything was written and flushed. A failure never leaves a
/// partial file behind, and an existing file at `path` is kept unless the write succeeds.
///
/// \throws IoError      "<path>: <problem>" if the extension is not .obj, .ply or .off, or the
///                      file cannot be written.
/// \throws InvalidInput if F holds an index outside V, or V a non-finite coordinate ("<path>:
///                      ..."; the file would be unreadable).
void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                const WriteMeshOptions& options = {});

}  // namespace genflow
