// SPDX-License-Identifier: MIT
// Binary glTF (.glb) for write_mesh() and write_animation(), through TinyGLTF: one mesh, one
// node, one scene (and an animation of its morph targets).
#pragma once

#include <string>
#include <vector>

#include "genflow/io/vertex_attributes.h"
#include "genflow/mesh.h"

namespace genflow::detail {

/// The bytes of a .glb file: positions and area-weighted vertex normals (float), vertex colours
/// as COLOR_0 (linear, as glTF has them), each named value as a float attribute "_NAME", and
/// 32-bit indices; a matte double-sided material.
[[nodiscard]] std::string encode_glb(const TriangleMesh& mesh, const VertexAttributes& attributes);

/// The bytes of a .glb file that plays `frames` (vertices of the mesh of `faces`, one frame
/// each) at `frames_per_second`: the mesh is the first frame, each later frame a morph target
/// (positions and normals) whose weight an animation of the node raises to 1 at the frame's
/// time and lowers again, linearly, by the next.
[[nodiscard]] std::string encode_animated_glb(const Eigen::MatrixX3i& faces,
                                              const std::vector<Eigen::MatrixX3d>& frames,
                                              const VertexAttributes& attributes,
                                              double frames_per_second);

}  // namespace genflow::detail
