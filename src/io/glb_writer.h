// SPDX-License-Identifier: MIT
// Binary glTF (.glb) for write_mesh(), through TinyGLTF: one mesh, one node, one scene.
#pragma once

#include <string>

#include "genflow/io/vertex_attributes.h"
#include "genflow/mesh.h"

namespace genflow::detail {

/// The bytes of a .glb file: positions and area-weighted vertex normals (float), vertex colours
/// as COLOR_0 (linear, as glTF has them), each named value as a float attribute "_NAME", and
/// 32-bit indices; a matte double-sided material.
[[nodiscard]] std::string encode_glb(const TriangleMesh& mesh, const VertexAttributes& attributes);

}  // namespace genflow::detail
