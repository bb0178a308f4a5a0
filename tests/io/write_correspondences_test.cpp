// SPDX-License-Identifier: MIT
#include "genflow/io/write_correspondences.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "genflow/exceptions.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

std::string read_text(const std::filesystem::path& path) {
    std::ifstream file(path);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

// One line per template vertex, after the `#` header: the face, the barycentric coordinates
// and the distance, to nine significant digits.
TEST(WriteCorrespondences, WritesOneLinePerVertexAfterTheHeader) {
    const test::TemporaryDirectory directory;
    const std::vector<SurfacePoint> points{
        {3, Eigen::Vector3d(0.25, 0.5, 0.25), Eigen::Vector3d::Zero(), 0.125},
        {0, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero(), 1.0 / 3}};
    write_correspondences(directory / "map.txt", points);
    std::istringstream text(read_text(directory / "map.txt"));
    std::string line;
    int header = 0;
    std::vector<std::string> rows;
    while (std::getline(text, line)) {
        if (line.starts_with("#")) {
            ++header;
        } else {
            rows.push_back(line);
        }
    }
    EXPECT_GE(header, 1);
    ASSERT_EQ(rows.size(), 2U);
    EXPECT_EQ(rows[0], "3 0.25 0.5 0.25 0.125");
    EXPECT_EQ(rows[1], "0 1 0 0 0.333333333");
}

// A file that cannot be written is an IoError naming it, and nothing is written.
TEST(WriteCorrespondences, FailureNamesThePathAndWritesNothing) {
    const test::TemporaryDirectory directory;
    const std::vector<SurfacePoint> points{
        {1, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d::Zero(), 0.5}};
    try {
        write_correspondences(directory / "missing" / "map.txt", points);
        FAIL() << "expected IoError";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("map.txt"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(directory / "missing"));
}

}  // namespace
}  // namespace genflow
