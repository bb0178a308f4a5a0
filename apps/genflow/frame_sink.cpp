// SPDX-License-Identifier: MIT
#include "frame_sink.h"

#include <iomanip>
#include <sstream>
#include <string>

#include "cli_support.h"
#include "genflow/io/atomic_file.h"
#include "genflow/io/write_animation.h"
#include "genflow/io/write_mesh.h"

namespace genflow::cli {

namespace {

// "frame_00042.ply": the name of frame `number` in a --frames directory.
std::string frame_name(int number) {
    std::ostringstream name;
    name << "frame_" << std::setw(5) << std::setfill('0') << number << ".ply";
    return name.str();
}

}  // namespace

FrameSink::FrameSink(std::optional<std::filesystem::path> path) : path_(std::move(path)) {
    if (!path_) {
        return;
    }
    animated_ = has_extension(*path_, ".glb");
    if (animated_) {
        check_output_path(*path_);
    } else {
        create_output_directory(*path_);
    }
}

void FrameSink::add(const TriangleMesh& mesh, int number) {
    if (!path_) {
        return;
    }
    if (!animated_) {
        write_mesh(*path_ / frame_name(number), mesh, {.ply_precision = PlyPrecision::Float});
        return;
    }
    if (frames_.empty()) {
        faces_ = mesh.F;
    }
    frames_.push_back(mesh.V);
}

void FrameSink::finish(const VertexAttributes& attributes) {
    if (animated_ && !frames_.empty()) {
        write_animation(*path_, faces_, frames_, attributes);
    }
}

}  // namespace genflow::cli
