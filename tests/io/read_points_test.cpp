// SPDX-License-Identifier: MIT
#include "genflow/io/read_points.h"

#include <gtest/gtest.h>

#include "genflow/exceptions.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

TEST(ReadPoints, ReadsXyzWithNormalsAndCommentsAndTheVerticesOfAMeshFile) {
    const test::TemporaryDirectory directory;
    test::write_bytes(directory / "scan.XYZ",
                      "# x y z, then a normal\n"
                      "0 0 0 0 0 1\r\n"
                      "\n"
                      "1 2.5 -3e-1   # a comment\n"
                      "\t4 5 6\n");
    const Eigen::MatrixX3d points = read_points(directory / "scan.XYZ");
    ASSERT_EQ(points.rows(), 3);
    EXPECT_EQ(points.row(1), Eigen::RowVector3d(1, 2.5, -0.3));
    EXPECT_EQ(points.row(2), Eigen::RowVector3d(4, 5, 6));

    test::write_bytes(directory / "cloud.obj", "v 1 2 3\nvn 0 0 1\nv 4 5 6\n");
    EXPECT_EQ(read_points(directory / "cloud.obj"),
              (Eigen::MatrixX3d(2, 3) << 1, 2, 3, 4, 5, 6).finished());
}

// The message names the file (and for XYZ the line) and says what is wrong.
void expect_points_refused(const std::string& name, const std::string& text,
                           const std::string& says) {
    const test::TemporaryDirectory directory;
    test::write_bytes(directory / name, text);
    try {
        (void)read_points(directory / name);
        ADD_FAILURE() << "accepted: " << text;
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_NE(message.find(says), std::string::npos) << message;
    }
}

TEST(ReadPoints, RefusesABadLineANonFiniteCoordinateOrNoPoint) {
    expect_points_refused("a.xyz", "0 0 0\n1 2\n", "line 2: expected 'x y z'");
    expect_points_refused("b.xyz", "0 0 0\n1 x 2\n",
                          "line 2: expected a finite coordinate, got 'x'");
    expect_points_refused("c.xyz", "1 inf 2\n", "line 1: expected a finite coordinate");
    expect_points_refused("d.xyz", "# nothing\n\n", "no point");
    expect_points_refused("e.obj", "v 1 nan 2\n", "point 0 has a non-finite coordinate");
}

}  // namespace
}  // namespace genflow
