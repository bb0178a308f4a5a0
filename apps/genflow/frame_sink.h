// SPDX-License-Identifier: MIT
// --frames PATH of smooth and match: a directory of frame_NNNNN.ply files, or, for a name
// ending in .glb, one animated glTF of all the frames (write_animation()).
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <vector>

#include "genflow/io/vertex_attributes.h"
#include "genflow/mesh.h"

namespace genflow::cli {

class FrameSink {
public:
    /// Nowhere without a path; else checks the place before any work: creates the directory,
    /// or checks that the .glb file can be written.
    explicit FrameSink(std::optional<std::filesystem::path> path);

    [[nodiscard]] bool active() const { return path_.has_value(); }

    /// Frame `number` (its file's number in a directory): written at once as float PLY, or kept
    /// for the animation.
    void add(const TriangleMesh& mesh, int number);

    /// Writes the animation of the kept frames with `attributes` (of the frames' vertices),
    /// in the caller's OutputTransaction; nothing for a directory.
    void finish(const VertexAttributes& attributes);

private:
    std::optional<std::filesystem::path> path_;
    bool animated_ = false;
    Eigen::MatrixX3i faces_;
    std::vector<Eigen::MatrixX3d> frames_;
};

}  // namespace genflow::cli
