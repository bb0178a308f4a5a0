// SPDX-License-Identifier: MIT
#include "genflow/mesh/boundary_loops.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/mesh/edges.h"
#include "genflow/mesh/face_selection.h"
#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

// The grid of `cells` × `cells` unit cells without the faces in the cells `cut` holds.
template <typename Cut>
TriangleMesh grid_without_cells(int cells, Cut cut) {
    const TriangleMesh grid = make_grid(cells, cells);
    return {grid.V, faces_where(grid.F, [&](Eigen::Index f) {
                const Eigen::RowVector3d c = (grid.V.row(grid.F(f, 0)) + grid.V.row(grid.F(f, 1)) +
                                              grid.V.row(grid.F(f, 2))) /
                                             3;
                return !cut(static_cast<int>(c.x()), static_cast<int>(c.y()));
            })};
}

// Every step of every loop is a boundary edge as its face runs it, and every boundary edge is
// one step of one loop.
void expect_loops_run_the_boundary(const TriangleMesh& mesh,
                                   const std::vector<std::vector<int>>& loops) {
    const Eigen::MatrixX2i oriented = oriented_boundary_edges(mesh.F);
    std::vector<int> used(static_cast<std::size_t>(oriented.rows()), 0);
    for (const auto& loop : loops) {
        for (std::size_t k = 0; k < loop.size(); ++k) {
            const int a = loop[k];
            const int b = loop[(k + 1) % loop.size()];
            for (Eigen::Index e = 0; e < oriented.rows(); ++e) {
                used[static_cast<std::size_t>(e)] += oriented(e, 0) == a && oriented(e, 1) == b;
            }
        }
    }
    EXPECT_EQ(used, std::vector<int>(used.size(), 1));
}

std::vector<std::size_t> sorted_sizes(const std::vector<std::vector<int>>& loops) {
    std::vector<std::size_t> sizes;
    for (const auto& loop : loops) {
        sizes.push_back(loop.size());
    }
    std::sort(sizes.begin(), sizes.end());
    return sizes;
}

TEST(BoundaryLoops, GridRimAndClosedSurface) {
    const TriangleMesh grid = make_grid(4);
    const auto loops = boundary_loops(grid);
    ASSERT_EQ(loops.size(), 1U);
    EXPECT_EQ(loops[0].size(), 16U);
    expect_loops_run_the_boundary(grid, loops);
    EXPECT_TRUE(boundary_loops(make_icosphere(2)).empty());
    EXPECT_THROW((void)boundary_loops(TriangleMesh{Eigen::MatrixX3d::Zero(2, 3),
                                                   Eigen::MatrixX3i::Constant(1, 3, 5)}),
                 InvalidInput);
}

// Two cells cut out of a 6×6 grid, touching at one corner: a loop around each (4 edges) and the
// rim's 24, where joining boundary edges at shared vertices would make the two holes one.
TEST(BoundaryLoops, HolesTouchingAtACornerAreLoopsOfTheirOwn) {
    const TriangleMesh holed = grid_without_cells(
        6, [](int x, int y) { return (x == 2 && y == 2) || (x == 3 && y == 3); });
    const auto loops = boundary_loops(holed);
    EXPECT_EQ(sorted_sizes(loops), (std::vector<std::size_t>{4, 4, 24}));
    expect_loops_run_the_boundary(holed, loops);
}

// A hole in the second row of cells whose faces reach down to the rim's vertices (the faces of
// the first row above its diagonals, leaving those below as teeth hung at the rim's vertices): the
// rim stays one loop of all the grid's 24 rim edges, the hole another.
TEST(BoundaryLoops, HoleTouchingTheRimIsALoopOfItsOwn) {
    const TriangleMesh grid = make_grid(6, 6);
    const TriangleMesh notched{
        grid.V, faces_where(grid.F, [&](Eigen::Index f) {
            const Eigen::RowVector3d c =
                (grid.V.row(grid.F(f, 0)) + grid.V.row(grid.F(f, 1)) + grid.V.row(grid.F(f, 2))) /
                3;
            return !(c.y() > 0.5 && c.y() < 2 && c.x() > 1 && c.x() < 4);
        })};
    const auto loops = boundary_loops(notched);
    ASSERT_EQ(loops.size(), 2U);
    expect_loops_run_the_boundary(notched, loops);
    const auto rim = std::find_if(loops.begin(), loops.end(), [](const std::vector<int>& loop) {
        return std::find(loop.begin(), loop.end(), 0) != loop.end();  // holds a corner
    });
    ASSERT_NE(rim, loops.end());
    EXPECT_EQ(rim->size(), 24U);  // the rim as the whole grid's
}

}  // namespace
}  // namespace genflow
