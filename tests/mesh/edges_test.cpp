// SPDX-License-Identifier: MIT
#include "genflow/mesh/edges.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

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

// Against a std::set of (min, max) pairs, on faces that repeat edges in every way a mesh can:
// duplicate and reversed faces, an edge of three faces, a repeated index, an isolated vertex.
TEST(Edges, AreTheSetOfTheFacesEdgesInOrder) {
    Eigen::MatrixX3i F(7, 3);
    F << 0, 1, 2, 2, 1, 0, 0, 1, 2, 1, 0, 3, 0, 1, 4, 5, 5, 6, 8, 6, 5;
    std::set<std::pair<int, int>> expected;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            const int a = F(f, k);
            const int b = F(f, (k + 1) % 3);
            if (a != b) {
                expected.insert({std::min(a, b), std::max(a, b)});
            }
        }
    }
    const Eigen::MatrixX2i E = unique_edges(F);
    ASSERT_EQ(E.rows(), static_cast<Eigen::Index>(expected.size()));
    Eigen::Index row = 0;
    for (const auto& [lo, hi] : expected) {
        EXPECT_EQ(E(row, 0), lo) << row;
        EXPECT_EQ(E(row, 1), hi) << row;
        ++row;
    }
}

TEST(Edges, BoundaryVerticesOfAGridAndAClosedMesh) {
    const TriangleMesh grid = make_grid(4);
    const std::vector<bool> boundary = boundary_vertices(grid.F, grid.V.rows());
    for (Eigen::Index i = 0; i < grid.V.rows(); ++i) {
        const double x = grid.V(i, 0);
        const double y = grid.V(i, 1);
        EXPECT_EQ(boundary[static_cast<std::size_t>(i)], x == 0 || x == 1 || y == 0 || y == 1) << i;
    }
    const TriangleMesh sphere = make_icosphere(1);
    const auto none = boundary_vertices(sphere.F, sphere.V.rows());
    EXPECT_EQ(std::count(none.begin(), none.end(), true), 0);
}

// A 4×4 grid's boundary is its 16 outer edges, each on the unit square's sides; two triangles
// sharing an edge have the other four.
TEST(Edges, BoundaryEdgesOfAGridTwoTrianglesAndAClosedMesh) {
    const TriangleMesh grid = make_grid(4);
    const Eigen::MatrixX2i edges = boundary_edges(grid.F);
    ASSERT_EQ(edges.rows(), 16);
    for (Eigen::Index e = 0; e < edges.rows(); ++e) {
        const Eigen::RowVector3d a = grid.V.row(edges(e, 0));
        const Eigen::RowVector3d b = grid.V.row(edges(e, 1));
        EXPECT_LT(edges(e, 0), edges(e, 1));
        EXPECT_TRUE((a.x() == b.x() && (a.x() == 0 || a.x() == 1)) ||
                    (a.y() == b.y() && (a.y() == 0 || a.y() == 1)))
            << a << " — " << b;
    }
    Eigen::MatrixX3i F(2, 3);
    F << 2, 1, 0, 1, 2, 3;
    Eigen::MatrixX2i expected(4, 2);
    expected << 0, 1, 0, 2, 1, 3, 2, 3;
    EXPECT_EQ(boundary_edges(F), expected);
    EXPECT_EQ(boundary_edges(make_icosphere(2).F).rows(), 0);
}

// The same edges as their faces run them: the grid's faces point to +z, so its rim runs
// counter-clockwise seen from above, each vertex left once and entered once.
TEST(Edges, OrientedBoundaryEdgesRunAsTheirFaces) {
    const TriangleMesh grid = make_grid(4);
    const Eigen::MatrixX2i oriented = oriented_boundary_edges(grid.F);
    const Eigen::MatrixX2i edges = boundary_edges(grid.F);
    ASSERT_EQ(oriented.rows(), edges.rows());
    std::vector<int> out(static_cast<std::size_t>(grid.V.rows()), 0);
    std::vector<int> in(static_cast<std::size_t>(grid.V.rows()), 0);
    const Eigen::RowVector3d centre(0.5, 0.5, 0);
    for (Eigen::Index e = 0; e < oriented.rows(); ++e) {
        EXPECT_EQ(std::minmax(oriented(e, 0), oriented(e, 1)),
                  std::minmax(edges(e, 0), edges(e, 1)));
        const Eigen::RowVector3d a = grid.V.row(oriented(e, 0)) - centre;
        const Eigen::RowVector3d b = grid.V.row(oriented(e, 1)) - centre;
        EXPECT_GT(a.x() * b.y() - a.y() * b.x(), 0);  // counter-clockwise about the centre
        ++out[static_cast<std::size_t>(oriented(e, 0))];
        ++in[static_cast<std::size_t>(oriented(e, 1))];
    }
    EXPECT_EQ(out, in);
    EXPECT_EQ(oriented_boundary_edges(make_icosphere(2).F).rows(), 0);
}

// Each vertex of a 4×4 grid has as many neighbours as edges at it (2 to 6), each edge seen
// from both ends; on an icosphere, 5 at the 12 original corners and 6 elsewhere.
TEST(Edges, VertexNeighboursAreTheOneRings) {
    const TriangleMesh grid = make_grid(4);
    const auto rings = vertex_neighbours(grid.F, grid.V.rows());
    ASSERT_EQ(rings.size(), static_cast<std::size_t>(grid.V.rows()));
    std::size_t ends = 0;
    for (std::size_t i = 0; i < rings.size(); ++i) {
        ends += rings[i].size();
        for (const Eigen::Index j : rings[i]) {
            const auto& back = rings[static_cast<std::size_t>(j)];
            EXPECT_NE(std::find(back.begin(), back.end(), static_cast<Eigen::Index>(i)),
                      back.end());
        }
    }
    EXPECT_EQ(ends, 2 * static_cast<std::size_t>(unique_edges(grid.F).rows()));
    const TriangleMesh sphere = make_icosphere(2);
    const auto sphere_rings = vertex_neighbours(sphere.F, sphere.V.rows());
    EXPECT_EQ(std::count_if(sphere_rings.begin(), sphere_rings.end(),
                            [](const auto& ring) { return ring.size() == 5; }),
              12);
    EXPECT_EQ(std::count_if(sphere_rings.begin(), sphere_rings.end(),
                            [](const auto& ring) { return ring.size() == 6; }),
              sphere.V.rows() - 12);
}

}  // namespace
}  // namespace genflow
