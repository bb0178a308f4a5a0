// SPDX-License-Identifier: MIT
// What write_mesh() and write_animation() require of the faces and attributes they write.
#pragma once

#include <filesystem>
#include <string>

#include "genflow/io/vertex_attributes.h"
#include "genflow/mesh.h"

namespace genflow::detail {

/// Throws InvalidInput "<path>: ..." unless each attribute has a finite row per vertex of
/// `mesh` (texture coordinates per corner: a row of table indices per face), and each value a
/// name of its own that a PLY header can hold.
/// Throws InvalidInput "<who>: face indices must lie in [0, vertices)" unless they do.
void check_face_indices(const std::string& who, const Eigen::MatrixX3i& faces,
                        Eigen::Index vertices);

void check_attributes(const std::filesystem::path& path, const TriangleMesh& mesh,
                      const VertexAttributes& attributes);

}  // namespace genflow::detail
