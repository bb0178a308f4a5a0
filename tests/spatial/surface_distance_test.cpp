// SPDX-License-Identifier: MIT
#include "genflow/spatial/surface_distance.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "genflow/exceptions.h"
#include "genflow/io/read_mesh.h"
#include "genflow/mesh/primitives.h"
#include "genflow/spatial/closest_point.h"
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

// An independent estimate: dense barycentric sampling of `from` and a brute-force scan of
// `to`'s faces. It is a lower bound of the true Hausdorff distance, and within the sampling
// radius of it.
struct SampledDistance {
    double max = 0;
    double mean = 0;
    double radius = 0;
};

SampledDistance sampled_distance(const TriangleMesh& from, const TriangleMesh& to, int k) {
    const TriangleBvh bvh(to);
    SampledDistance s;
    double area = 0;
    for (Eigen::Index f = 0; f < from.F.rows(); ++f) {
        const Eigen::Vector3d a = from.V.row(from.F(f, 0)).transpose();
        const Eigen::Vector3d b = from.V.row(from.F(f, 1)).transpose();
        const Eigen::Vector3d c = from.V.row(from.F(f, 2)).transpose();
        const double face_area = 0.5 * (b - a).cross(c - a).norm();
        s.radius =
            std::max(s.radius, std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()}) / k);
        double sum = 0;
        int count = 0;
        for (int i = 0; i <= k; ++i) {
            for (int j = 0; i + j <= k; ++j) {
                const Eigen::Vector3d p = a + (static_cast<double>(i) / k) * (b - a) +
                                          (static_cast<double>(j) / k) * (c - a);
                const double d = bvh.distance(p);
                s.max = std::max(s.max, d);
                sum += d;
                ++count;
            }
        }
        s.mean += face_area * sum / count;
        area += face_area;
    }
    s.mean /= area;
    return s;
}

TEST(SurfaceDistance, AgreesWithDenseSamplingOnARealPairWithinTheStatedBounds) {
    const auto data = test::data_directory();
    if (!data) {
        GTEST_SKIP() << "no data directory (set GENFLOW_DATA)";
    }
    // The small pairs of pairs.json: template against ground-truth target.
    for (const char* pair :
         {"faust_000_001_small", "tosca_cat_0_4_small", "tosca_centaur_0_5_small"}) {
        const TriangleMesh A =
            read_mesh(*data / "matching/small" / (std::string(pair) + "_template.ply"));
        const TriangleMesh B =
            read_mesh(*data / "matching/small" / (std::string(pair) + "_target.ply"));
        const SurfaceDistances d = surface_distances(A, B);
        const SampledDistance s = sampled_distance(A, B, 4);
        // sampled ≤ true ≤ reported upper bound, and true ≤ sampled + radius (1-Lipschitz).
        EXPECT_LE(s.max, d.a_to_b.hausdorff_upper_bound + 1e-12) << pair;
        EXPECT_LE(d.a_to_b.hausdorff, s.max + s.radius) << pair;
        EXPECT_NEAR(d.a_to_b.mean, s.mean, d.a_to_b.mean_error_bound + s.radius) << pair;
        EXPECT_GT(d.a_to_b.mean, 0) << pair;
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
