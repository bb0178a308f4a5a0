// SPDX-License-Identifier: MIT
#include "genflow/operators/mesh_size.h"

#include <gtest/gtest.h>

#include <cmath>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

TEST(MeshSize, BoundingBoxDiagonalOfKnownShapes) {
    EXPECT_NEAR(bounding_box_diagonal(make_grid(3, 2.0)), 2 * std::sqrt(2.0), 1e-15);
    EXPECT_NEAR(bounding_box_diagonal(make_torus(40, 8, 1.0, 0.4)),
                std::sqrt(2.8 * 2.8 + 2.8 * 2.8 + 0.8 * 0.8), 1e-2);
    EXPECT_EQ(bounding_box_diagonal(TriangleMesh{}), 0.0);
}

TEST(MeshSize, MeanEdgeLengthCountsEachEdgeOnce) {
    // A 1×1 grid of cell size 1: 4 unit edges and one diagonal of √2.
    EXPECT_NEAR(mean_edge_length(make_grid(1)), (4 + std::sqrt(2.0)) / 5, 1e-15);
    // 2×2 grid of cell 0.5: 12 edges of 0.5 and 4 diagonals of √2/2.
    EXPECT_NEAR(mean_edge_length(make_grid(2)), (12 * 0.5 + 4 * std::sqrt(0.5)) / 16, 1e-15);
}

TEST(MeshSize, RejectsNonFinitePositions) {
    TriangleMesh mesh = make_grid(1);
    mesh.V(0, 0) = std::nan("");
    EXPECT_THROW((void)bounding_box_diagonal(mesh), InvalidInput);
    EXPECT_THROW((void)mean_edge_length(mesh), InvalidInput);
}

}  // namespace
}  // namespace genflow
