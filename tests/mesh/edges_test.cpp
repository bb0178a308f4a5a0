// SPDX-License-Identifier: MIT
#include "genflow/mesh/edges.h"

#include <gtest/gtest.h>

#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

TEST(Edges, EulerFormulaOnClosedMeshes) {
    const TriangleMesh sphere = make_icosphere(3);
    EXPECT_EQ(sphere.V.rows() - unique_edges(sphere.F).rows() + sphere.F.rows(), 2);
    const TriangleMesh torus = make_torus(10, 7);
    EXPECT_EQ(torus.V.rows() - unique_edges(torus.F).rows() + torus.F.rows(), 0);
}

TEST(Edges, AreSortedUniqueAndOrdered) {
    Eigen::MatrixX3i F(2, 3);
    F << 2, 1, 0, 1, 2, 3;
    Eigen::MatrixX2i expected(5, 2);
    expected << 0, 1, 0, 2, 1, 2, 1, 3, 2, 3;
    EXPECT_EQ(unique_edges(F), expected);
}

}  // namespace
}  // namespace genflow
