// SPDX-License-Identifier: MIT
// libFuzzer entry point for the readers that take a path (points, landmarks, reference points,
// part files, eval's pairs file), compiled once per reader (GENFLOW_FUZZ_READER names one of
// the functions below): the input is written to a file of the reader's kind and read; any byte
// string must be read or raise IoError, never crash, hang or allocate without bound.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "genflow/exceptions.h"
#include "genflow/io/read_correspondences.h"
#include "genflow/io/read_landmarks.h"
#include "genflow/io/read_part_model.h"
#include "genflow/io/read_points.h"
#include "genflow/io/read_reference_points.h"
#include "genflow/mesh.h"
#include "pairs_file.h"

namespace {

// The template's vertex count the per-vertex readers check against.
constexpr Eigen::Index kVertices = 4;

const std::filesystem::path& directory() {
    static const std::filesystem::path path = [] {
        std::string name =
            (std::filesystem::temp_directory_path() / "genflow-fuzz-XXXXXX").string();
        if (::mkdtemp(name.data()) == nullptr) {
            std::abort();
        }
        return std::filesystem::path(name);
    }();
    return path;
}

std::filesystem::path written(const std::string& name, std::string_view bytes) {
    const std::filesystem::path path = directory() / name;
    std::ofstream(path, std::ios::binary)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path;
}

void xyz_points(std::string_view bytes) {
    (void)genflow::read_points(written("in.xyz", bytes));
}

void ply_points(std::string_view bytes) {
    (void)genflow::read_points(written("in.ply", bytes));
}

void landmarks(std::string_view bytes) {
    static const genflow::TriangleMesh target{
        (Eigen::MatrixX3d(4, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1).finished(),
        (Eigen::MatrixX3i(4, 3) << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3).finished()};
    (void)genflow::read_landmarks(written("in.txt", bytes), kVertices, target);
}

void reference_points(std::string_view bytes) {
    (void)genflow::read_reference_points(written("in.vts", bytes), kVertices);
}

// A part tree of two parts beside labels, for the fuzzed side to be read against.
const char* const kTree =
    R"({"parts": [{"name": "a", "parent": null, "joint_center": [0, 0, 0]},
                  {"name": "b", "parent": "a", "joint_center": [1, 0, 0]}]})";

void part_tree(std::string_view bytes) {
    genflow::PartFiles files{written("tree.json", bytes)};
    files.labels = written("labels.txt", "0\n0\n1\n1\n");
    (void)genflow::read_part_model(files, kVertices);
}

void part_labels(std::string_view bytes) {
    genflow::PartFiles files{written("tree.json", kTree)};
    files.labels = written("labels.txt", bytes);
    (void)genflow::read_part_model(files, kVertices);
}

void part_weights(std::string_view bytes) {
    genflow::PartFiles files{written("tree.json", kTree)};
    files.weights = written("weights.txt", bytes);
    (void)genflow::read_part_model(files, kVertices);
}

void correspondences(std::string_view bytes) {
    static const genflow::TriangleMesh target{
        (Eigen::MatrixX3d(4, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1).finished(),
        (Eigen::MatrixX3i(4, 3) << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3).finished()};
    (void)genflow::read_correspondences(written("map.txt", bytes), target, kVertices);
}

void pairs(std::string_view bytes) {
    (void)genflow::cli::read_pairs_file(written("pairs.json", bytes), directory());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        GENFLOW_FUZZ_READER(std::string_view(reinterpret_cast<const char*>(data), size));
    } catch (const genflow::IoError&) {
    }
    return 0;
}
