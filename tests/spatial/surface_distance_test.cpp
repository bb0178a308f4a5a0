// SPDX-License-Identifier: MIT
#include "genflow/spatial/surface_distance.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <tuple>
#include <utility>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/spatial/closest_point.h"
#include "genflow/threads.h"
#include "support/reference_distances.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

TEST(SurfaceDistance, ParallelSquaresHaveKnownDistances) {
    const TriangleMesh A = make_grid(5, 1.0);  // [0,1]² at z = 0
    TriangleMesh B = make_grid(7, 1.4);        // [−0.2,1.2]² at z = 0.3
    B.V.rowwise() += Eigen::RowVector3d(-0.2, -0.2, 0.3);
    const SurfaceDistances d = surface_distances(A, B, {.hausdorff_tolerance = 1e-10});
    EXPECT_NEAR(d.a_to_b.hausdorff, 0.3, 1e-9);
    EXPECT_NEAR(d.b_to_a.hausdorff, std::sqrt(0.17), 1e-9);  // B's corners
    EXPECT_NEAR(d.hausdorff, std::sqrt(0.17), 1e-9);
    EXPECT_NEAR(d.a_to_b.mean, 0.3, 1e-12);
    EXPECT_NEAR(d.a_to_b.rms, 0.3, 1e-12);
    EXPECT_GT(d.b_to_a.mean, 0.3);
    EXPECT_NEAR(d.a_to_b.area, 1.0, 1e-12);
}

TEST(SurfaceDistance, FindsAMaximumInsideAFace) {
    // A: equilateral triangle of side 1. B: three small triangles touching A's corners from
    // outside. The farthest point of A from B is A's centre, at the circumradius 1/√3.
    const double h = std::sqrt(3.0) / 2;
    TriangleMesh A;
    A.V.resize(3, 3);
    A.V << 0, 0, 0, 1, 0, 0, 0.5, h, 0;
    A.F.resize(1, 3);
    A.F << 0, 1, 2;
    TriangleMesh B;
    B.V.resize(9, 3);
    B.F.resize(3, 3);
    const Eigen::RowVector3d centre = A.V.colwise().mean();
    for (int k = 0; k < 3; ++k) {
        const Eigen::RowVector3d corner = A.V.row(k);
        const Eigen::RowVector3d out = (corner - centre).normalized();
        const Eigen::RowVector3d side(-out[1], out[0], 0);
        B.V.row(3 * k) = corner;
        B.V.row(3 * k + 1) = corner + 0.01 * out + 0.005 * side;
        B.V.row(3 * k + 2) = corner + 0.01 * out - 0.005 * side;
        B.F.row(k) << 3 * k, 3 * k + 1, 3 * k + 2;
    }
    const SurfaceDistances d = surface_distances(A, B, {.hausdorff_tolerance = 1e-10});
    EXPECT_NEAR(d.a_to_b.hausdorff, 1 / std::sqrt(3.0), 1e-9);
    EXPECT_LT((d.a_to_b.farthest_point - centre.transpose()).norm(), 1e-4);
    EXPECT_GE(d.a_to_b.hausdorff_upper_bound, d.a_to_b.hausdorff);
}

TEST(SurfaceDistance, IdenticalMeshesAreAtZero) {
    const TriangleMesh mesh = test::noisy_icosphere(2);
    const SurfaceDistances d = surface_distances(mesh, mesh);
    EXPECT_LT(d.hausdorff, 1e-12);
    EXPECT_LT(d.mean, 1e-12);
}

// A bumpy sphere against a coarse smooth one: the maxima lie inside faces, so the split-and-prune
// search must find them. Dense sampling (tests/support/reference_distances.h) brackets them:
// sample max ≤ true ≤ sample max + grid spacing.
TEST(SurfaceDistance, HausdorffIsBracketedByDenseSampling) {
    const TriangleMesh bumpy = test::noisy_icosphere(3, 0.3);
    const TriangleMesh smooth = make_icosphere(1, 1.0);
    const double tolerance = 1e-6;
    const SurfaceDistances d = surface_distances(bumpy, smooth, {.hausdorff_tolerance = tolerance});
    for (const auto& [one_sided, from, to] :
         {std::tuple{d.a_to_b, &bumpy, &smooth}, std::tuple{d.b_to_a, &smooth, &bumpy}}) {
        const test::SampledDistance sampled = test::sampled_distance(*from, *to, 24);
        EXPECT_GE(one_sided.hausdorff, sampled.max - 1e-12);
        EXPECT_LE(one_sided.hausdorff, sampled.max + sampled.radius);
        EXPECT_LE(one_sided.hausdorff_upper_bound, one_sided.hausdorff + tolerance + 1e-15);
        const SurfacePoint at = TriangleBvh(*to).closest_point(one_sided.farthest_point);
        EXPECT_NEAR(at.distance, one_sided.hausdorff, 1e-15);
    }
}

TEST(SurfaceDistance, HausdorffAloneIsTheSameHausdorff) {
    const TriangleMesh bumpy = test::noisy_icosphere(3, 0.3);
    const TriangleMesh smooth = make_icosphere(2, 1.0);
    const SurfaceDistances full = surface_distances(bumpy, smooth);
    const SurfaceDistances alone = surface_distances(bumpy, smooth, {.mean_and_rms = false});
    EXPECT_EQ(alone.hausdorff, full.hausdorff);
    EXPECT_EQ(alone.a_to_b.hausdorff_upper_bound, full.a_to_b.hausdorff_upper_bound);
    EXPECT_EQ(alone.b_to_a.farthest_point, full.b_to_a.farthest_point);
    EXPECT_GT(full.mean, 0);
    EXPECT_EQ(alone.mean, 0);
    EXPECT_EQ(alone.a_to_b.rms, 0);
}

TEST(SurfaceDistance, ThreadCountChangesNothing) {
    const TriangleMesh bumpy = test::noisy_icosphere(3, 0.3);
    const TriangleMesh smooth = make_icosphere(2, 1.0);
    const int before = thread_count();
    set_thread_count(1);
    const SurfaceDistances one = surface_distances(bumpy, smooth);
    set_thread_count(2);
    const SurfaceDistances two = surface_distances(bumpy, smooth);
    set_thread_count(before);
    for (const auto& [x, y] :
         {std::pair{one.a_to_b, two.a_to_b}, std::pair{one.b_to_a, two.b_to_a}}) {
        EXPECT_EQ(x.hausdorff, y.hausdorff);
        EXPECT_EQ(x.hausdorff_upper_bound, y.hausdorff_upper_bound);
        EXPECT_EQ(x.farthest_point, y.farthest_point);
        EXPECT_EQ(x.mean, y.mean);
        EXPECT_EQ(x.rms, y.rms);
    }
}

TEST(SurfaceDistance, RejectsBadInput) {
    const TriangleMesh mesh = make_icosphere(1);
    EXPECT_THROW((void)surface_distances(mesh, TriangleMesh{}), InvalidInput);
    EXPECT_THROW((void)surface_distances(mesh, mesh, {.hausdorff_tolerance = -1}), InvalidInput);
    EXPECT_THROW((void)surface_distances(mesh, mesh, {.quadrature_length = NAN}), InvalidInput);
}

}  // namespace
}  // namespace genflow
