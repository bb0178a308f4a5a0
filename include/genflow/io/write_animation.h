// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "genflow/io/vertex_attributes.h"

namespace genflow {

/// Options of write_animation().
struct AnimationOptions {
    double frames_per_second = 24;  ///< the rate the frames play at (a film's)
};

/// Writes `frames` (the vertex positions of one mesh, its faces `faces`, at successive moments:
/// a flow's steps, a match's frames at the template's resolution) to `path` as one binary glTF
/// (.glb) that plays them: the first frame is the mesh, with `attributes` (colours, texture
/// coordinates, values, as write_mesh() writes them to .glb), and each later frame a morph
/// target that an animation blends in and out linearly at `frames_per_second`. Web viewers
/// (three.js, model-viewer), Blender and game engines play it. Written atomically, as
/// write_mesh().
/// \throws IoError      unless `path` ends in .glb; when the file cannot be written.
/// \throws InvalidInput without frames, for a frame whose rows are not the first's or with a
///                      non-finite coordinate, for faces outside the vertices, and for
///                      attributes write_mesh() would refuse.
void write_animation(const std::filesystem::path& path, const Eigen::MatrixX3i& faces,
                     const std::vector<Eigen::MatrixX3d>& frames,
                     const VertexAttributes& attributes = {}, const AnimationOptions& options = {});

}  // namespace genflow
