// SPDX-License-Identifier: MIT
#include "spatial/surface_paths.h"

#include <gtest/gtest.h>

#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

TEST(SurfacePaths, EveryVertexGoesToTheSourceNearestAlongTheEdges) {
    const TriangleMesh grid = make_grid(12, 1.0);
    const detail::ChordGraph edges = detail::chord_graph(grid, 1);
    // Two opposite corners and the centre; vertex 0 twice (a repeated source counts once).
    const std::vector<Eigen::Index> sources{0, 0, grid.V.rows() - 1, grid.V.rows() / 2};
    const std::vector<Eigen::Index> nearest = detail::nearest_sources(edges, sources);
    std::vector<Eigen::VectorXd> lengths;
    for (const Eigen::Index s : sources) {
        lengths.push_back(detail::path_lengths_from(edges, s));
    }
    ASSERT_EQ(nearest.size(), static_cast<std::size_t>(grid.V.rows()));
    std::vector<int> count(sources.size(), 0);
    for (Eigen::Index v = 0; v < grid.V.rows(); ++v) {
        const Eigen::Index label = nearest[static_cast<std::size_t>(v)];
        ASSERT_GE(label, 0);
        ASSERT_NE(label, 1);  // the repeated source is the first one's
        ++count[static_cast<std::size_t>(label)];
        for (const Eigen::VectorXd& other : lengths) {
            EXPECT_LE(lengths[static_cast<std::size_t>(label)](v), other(v) + 1e-12) << v;
        }
    }
    for (const std::size_t s : {0U, 2U, 3U}) {
        EXPECT_GT(count[s], 20);  // each source has a region of its own
    }
}

TEST(SurfacePaths, ComponentsWithoutASourceAreUnreached) {
    TriangleMesh two = make_icosphere(1);
    const Eigen::Index n = two.V.rows();
    TriangleMesh both{Eigen::MatrixX3d(2 * n, 3), Eigen::MatrixX3i(2 * two.F.rows(), 3)};
    both.V << two.V, two.V.rowwise() + Eigen::RowVector3d(3, 0, 0);
    both.F << two.F, two.F.array() + static_cast<int>(n);
    const std::vector<Eigen::Index> nearest =
        detail::nearest_sources(detail::chord_graph(both, 1), {5});
    for (Eigen::Index v = 0; v < 2 * n; ++v) {
        EXPECT_EQ(nearest[static_cast<std::size_t>(v)], v < n ? 0 : -1) << v;
    }
}

}  // namespace
}  // namespace genflow
