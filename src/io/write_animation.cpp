// SPDX-License-Identifier: MIT
#include "genflow/io/write_animation.h"

#include <cmath>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/io/atomic_file.h"
#include "io/attribute_checks.h"
#include "io/glb_writer.h"
#include "io/parse_context.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

void check_frames(const std::filesystem::path& path, const Eigen::MatrixX3i& faces,
                  const std::vector<Eigen::MatrixX3d>& frames) {
    if (frames.empty()) {
        throw InvalidInput(path.string() + ": an animation needs a frame");
    }
    const Eigen::Index vertices = frames.front().rows();
    detail::check_face_indices(path.string(), faces, vertices);
    for (std::size_t k = 0; k < frames.size(); ++k) {
        if (frames[k].rows() != vertices || !detail::all_finite(frames[k])) {
            throw InvalidInput(path.string() + ": frame " + std::to_string(k) + " needs " +
                               std::to_string(vertices) + " finite vertices, as the first");
        }
    }
}

}  // namespace

void write_animation(const std::filesystem::path& path, const Eigen::MatrixX3i& faces,
                     const std::vector<Eigen::MatrixX3d>& frames,
                     const VertexAttributes& attributes, const AnimationOptions& options) {
    if (!detail::iequals(path.extension().string(), ".glb")) {
        throw IoError(path.string() + ": an animation is written as binary glTF (.glb)");
    }
    if (!(options.frames_per_second > 0) || !std::isfinite(options.frames_per_second)) {
        throw InvalidInput("write_animation: frames_per_second must be positive and finite");
    }
    check_frames(path, faces, frames);
    detail::check_attributes(path, TriangleMesh{frames.front(), faces}, attributes);
    write_file_atomically(
        path, detail::encode_animated_glb(faces, frames, attributes, options.frames_per_second));
}

}  // namespace genflow
