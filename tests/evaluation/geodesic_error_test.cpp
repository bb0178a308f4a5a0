// SPDX-License-Identifier: MIT
#include "genflow/evaluation/geodesic_error.h"

#include <gtest/gtest.h>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

// The point of `mesh` at `weight` of the way from vertex a to vertex b (an edge), as a map
// would give it: a face holding both and barycentric coordinates on its corners.
SurfacePoint on_edge(const TriangleMesh& mesh, Eigen::Index a, Eigen::Index b, double weight) {
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        int at_a = -1;
        int at_b = -1;
        for (int c = 0; c < 3; ++c) {
            at_a = mesh.F(f, c) == a ? c : at_a;
            at_b = mesh.F(f, c) == b ? c : at_b;
        }
        if (at_a >= 0 && at_b >= 0) {
            SurfacePoint point;
            point.face = f;
            point.barycentric.setZero();
            point.barycentric(at_a) = 1 - weight;
            point.barycentric(at_b) = weight;
            return point;
        }
    }
    throw std::logic_error("no face holds that edge");
}

// A 10 × 10 grid of side 2 (edges 0.2, √area = 2): along its bottom row the shortest edge path
// is the row itself.
TEST(GeodesicError, MeasuresEdgePathsOverTheRootOfTheArea) {
    const TriangleMesh grid = make_grid(10, 2.0);
    const GeodesicErrorMeasure measure(grid);
    EXPECT_DOUBLE_EQ(measure.unit(), 2.0);
    // Reference point 0 belongs at vertex 0 and was put on vertex 4; reference point 1 belongs
    // at vertex 0 too and was put 0.3 of the way from vertex 4 to 5; reference point 2 was put
    // where it belongs, vertex 7.
    const std::vector<SurfacePoint> mapped{on_edge(grid, 4, 5, 0), on_edge(grid, 4, 5, 0.3),
                                           on_edge(grid, 7, 8, 0)};
    const GeodesicErrors errors = measure.errors(mapped, {0, 0, 7});
    EXPECT_NEAR(errors.to_vertex(0), 0.8 / 2, 1e-12);
    EXPECT_NEAR(errors.to_point(0), 0.8 / 2, 1e-12);
    EXPECT_NEAR(errors.to_vertex(1), 0.8 / 2, 1e-12);          // snapped to vertex 4
    EXPECT_NEAR(errors.to_point(1), (0.8 + 0.06) / 2, 1e-12);  // 0.3 of an edge further
    EXPECT_EQ(errors.to_vertex(2), 0);
    EXPECT_EQ(errors.to_point(2), 0);
}

TEST(GeodesicError, AnotherComponentCountsAsOneUnit) {
    const TriangleMesh sphere = make_icosphere(1);
    const Eigen::Index n = sphere.V.rows();
    TriangleMesh both{Eigen::MatrixX3d(2 * n, 3), Eigen::MatrixX3i(2 * sphere.F.rows(), 3)};
    both.V << sphere.V, sphere.V.rowwise() + Eigen::RowVector3d(3, 0, 0);
    both.F << sphere.F, sphere.F.array() + static_cast<int>(n);
    const GeodesicErrorMeasure measure(both);
    const Eigen::Index far = sphere.F(0, 0) + n;
    const GeodesicErrors errors = measure.errors({on_edge(both, far, sphere.F(0, 1) + n, 0)}, {0});
    EXPECT_EQ(errors.to_vertex(0), 1.0);
    EXPECT_EQ(errors.to_point(0), 1.0);
}

// A map of every template vertex measured at the reference points only: template vertices 2
// and 0 are the reference points, and the map's entry for vertex 1 is never read.
TEST(GeodesicError, MeasuresAWholeMapAtTheTemplatesReferenceVertices) {
    const TriangleMesh grid = make_grid(10, 2.0);
    const GeodesicErrorMeasure measure(grid);
    const std::vector<SurfacePoint> map{on_edge(grid, 7, 8, 0), on_edge(grid, 1, 2, 0.5),
                                        on_edge(grid, 4, 5, 0)};
    const GeodesicErrors errors = measure.errors_at(map, {2, 0}, {0, 7});
    ASSERT_EQ(errors.to_vertex.size(), 2);
    EXPECT_NEAR(errors.to_vertex(0), 0.8 / 2, 1e-12);
    EXPECT_EQ(errors.to_vertex(1), 0);
    EXPECT_THROW((void)measure.errors_at(map, {3}, {0}), InvalidInput);
    EXPECT_THROW((void)measure.errors_at(map, {-1}, {0}), InvalidInput);
}

TEST(GeodesicError, RefusesMismatchedOrOutOfRangeInput) {
    const TriangleMesh grid = make_grid(2, 1.0);
    const GeodesicErrorMeasure measure(grid);
    const SurfacePoint point = on_edge(grid, 0, 1, 0.5);
    EXPECT_THROW((void)measure.errors({point}, {0, 1}), InvalidInput);
    EXPECT_THROW((void)measure.errors({point}, {grid.V.rows()}), InvalidInput);
    SurfacePoint outside = point;
    outside.face = grid.F.rows();
    EXPECT_THROW((void)measure.errors({outside}, {0}), InvalidInput);
    EXPECT_THROW(GeodesicErrorMeasure(TriangleMesh{grid.V, Eigen::MatrixX3i(0, 3)}), InvalidInput);
}

}  // namespace
}  // namespace genflow
