// SPDX-License-Identifier: MIT
#include "genflow/operators/normals.h"

#include <gtest/gtest.h>

#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

TEST(Normals, PointOutwardOnASphere) {
    const TriangleMesh mesh = test::noisy_icosphere(3, 0.1);
    const Eigen::MatrixX3d N = vertex_normals(mesh);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        EXPECT_NEAR(N.row(i).norm(), 1.0, 1e-14);
        EXPECT_GT(N.row(i).dot(mesh.V.row(i).normalized()), 0.9) << "vertex " << i;
    }
    const Eigen::MatrixX3d FN = face_normals(mesh);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        EXPECT_GT(FN.row(f).dot(mesh.V.row(mesh.F(f, 0))), 0) << "face " << f;
    }
}

TEST(Normals, PointOutwardOnATorus) {
    const TriangleMesh mesh = make_torus(24, 12);
    const Eigen::MatrixX3d N = vertex_normals(mesh);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        // Outward from the tube's centre circle.
        Eigen::RowVector3d centre = mesh.V.row(i);
        centre[2] = 0;
        centre = centre.normalized();
        EXPECT_GT(N.row(i).dot((mesh.V.row(i) - centre).normalized()), 0.99) << "vertex " << i;
    }
}

TEST(Normals, AreZeroWhereUndefined) {
    TriangleMesh mesh;
    mesh.V.resize(4, 3);
    mesh.V << 0, 0, 0, 1, 0, 0, 2, 0, 0, 5, 5, 5;  // a flat face and an unreferenced vertex
    mesh.F.resize(1, 3);
    mesh.F << 0, 1, 2;
    EXPECT_EQ(vertex_normals(mesh).norm(), 0.0);
    EXPECT_EQ(face_normals(mesh).norm(), 0.0);
}

}  // namespace
}  // namespace genflow
