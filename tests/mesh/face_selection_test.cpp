// SPDX-License-Identifier: MIT
#include "genflow/mesh/face_selection.h"

#include <gtest/gtest.h>

#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

TEST(FaceSelection, KeepsTheChosenRowsInOrder) {
    const TriangleMesh sphere = make_icosphere(1);
    const Eigen::MatrixX3i odd = faces_where(sphere.F, [](Eigen::Index f) { return f % 2 == 1; });
    ASSERT_EQ(odd.rows(), sphere.F.rows() / 2);
    for (Eigen::Index k = 0; k < odd.rows(); ++k) {
        EXPECT_EQ(odd.row(k), sphere.F.row(2 * k + 1));
    }
    EXPECT_EQ(faces_where(sphere.F, [](Eigen::Index) { return false; }).rows(), 0);
}

TEST(FaceSelection, FlagsTheVerticesFacesUse) {
    // Two triangles over five vertices: vertex 2 is on none.
    Eigen::MatrixX3i F(2, 3);
    F << 0, 1, 3, 3, 1, 4;
    const std::vector<bool> used = vertices_on_faces(F, 5);
    EXPECT_EQ(used, (std::vector<bool>{true, true, false, true, true}));
    EXPECT_EQ(vertices_on_faces(Eigen::MatrixX3i(0, 3), 2), (std::vector<bool>{false, false}));
    EXPECT_EQ(vertices_used_by(F, 5), (std::vector<Eigen::Index>{0, 1, 3, 4}));
    EXPECT_TRUE(vertices_used_by(Eigen::MatrixX3i(0, 3), 2).empty());
}

}  // namespace
}  // namespace genflow
