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
                      "1 2.5 -3e-1 0 2 0  # a comment\n"
                      "\t4 5 6 1 0 0 0.7\n");
    const PointCloud cloud = read_points(directory / "scan.XYZ");
    ASSERT_EQ(cloud.points.rows(), 3);
    EXPECT_EQ(cloud.points.row(1), Eigen::RowVector3d(1, 2.5, -0.3));
    EXPECT_EQ(cloud.points.row(2), Eigen::RowVector3d(4, 5, 6));
    ASSERT_EQ(cloud.normals.rows(), 3);
    EXPECT_EQ(cloud.normals.row(1), Eigen::RowVector3d(0, 2, 0));

    test::write_bytes(directory / "bare.xyz", "0 0 0\n1 0 0\n");
    EXPECT_EQ(read_points(directory / "bare.xyz").normals.rows(), 0);
    test::write_bytes(directory / "cloud.obj", "v 1 2 3\nvn 0 0 1\nv 4 5 6\n");
    const PointCloud obj = read_points(directory / "cloud.obj");
    EXPECT_EQ(obj.points, (Eigen::MatrixX3d(2, 3) << 1, 2, 3, 4, 5, 6).finished());
    EXPECT_EQ(obj.normals.rows(), 0);
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
    expect_points_refused("b.xyz", "0 0 0\n1 x 2\n", "line 2: expected a finite number, got 'x'");
    expect_points_refused("c.xyz", "1 inf 2\n", "line 1: expected a finite number");
    expect_points_refused("f.xyz", "0 0 0 0 0 1\n1 0 0\n",
                          "line 2: expected 'x y z nx ny nz', as on the first point's line");
    expect_points_refused("g.xyz", "0 0 0 0 0 0\n", "line 1: the normal is zero");
    expect_points_refused("d.xyz", "# nothing\n\n", "no point");
    expect_points_refused("e.obj", "v 1 nan 2\n", "point 0 has a non-finite coordinate");
}

}  // namespace
}  // namespace genflow
