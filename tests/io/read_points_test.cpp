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
                      "\xEF\xBB\xBF# x y z, then a normal\n"
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

// A scanner's PLY gives each vertex its normal, named nx, ny, nz or (PCL) normal_x, …, in text
// or binary; a PLY without them gives none.
TEST(ReadPoints, ReadsThePlyVerticesNormals) {
    const test::TemporaryDirectory directory;
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
        "property float y\nproperty float z\n";
    test::write_bytes(directory / "scan.ply", header +
                                                  "property float nx\nproperty float ny\n"
                                                  "property float nz\nend_header\n"
                                                  "0 0 0 0 0 1\n1 2 3 0 -2 0\n");
    const PointCloud text = read_points(directory / "scan.ply");
    EXPECT_EQ(text.points.row(1), Eigen::RowVector3d(1, 2, 3));
    EXPECT_EQ(text.normals, (Eigen::MatrixX3d(2, 3) << 0, 0, 1, 0, -2, 0).finished());

    std::string binary =
        "ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
        "property double normal_x\nproperty double normal_y\n"
        "property double normal_z\nproperty double x\nproperty double y\n"
        "property double z\nend_header\n";
    for (const double value : {0.0, 1.0, 0.0, 4.0, 5.0, 6.0}) {
        binary.append(reinterpret_cast<const char*>(&value), sizeof value);
    }
    test::write_bytes(directory / "pcl.ply", binary);
    const PointCloud pcl = read_points(directory / "pcl.ply");
    EXPECT_EQ(pcl.points.row(0), Eigen::RowVector3d(4, 5, 6));
    EXPECT_EQ(pcl.normals.row(0), Eigen::RowVector3d(0, 1, 0));

    test::write_bytes(directory / "bare.ply", header + "end_header\n0 0 0\n1 2 3\n");
    EXPECT_EQ(read_points(directory / "bare.ply").normals.rows(), 0);
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
    expect_points_refused("h.ply",
                          "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                          "property float y\nproperty float z\nproperty float nx\n"
                          "property float ny\nproperty float nz\nend_header\n"
                          "0 0 0 0 0 1\n1 0 0 0 0 0\n",
                          "point 1: the normal is zero");
}

}  // namespace
}  // namespace genflow
