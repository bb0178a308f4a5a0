// SPDX-License-Identifier: MIT
#include "genflow/spatial/closest_point.h"

#include <gtest/gtest.h>

#include <random>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

Eigen::Vector3d random_point(std::mt19937& generator, double scale) {
    std::uniform_real_distribution<double> uniform(-scale, scale);
    return {uniform(generator), uniform(generator), uniform(generator)};
}

// No point of the triangle (sampled densely) is nearer than the returned one.
void expect_optimal(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    const Eigen::Vector3d& c) {
    const Eigen::Vector3d w = closest_point_on_triangle(p, a, b, c);
    ASSERT_GE(w.minCoeff(), -1e-15);
    ASSERT_NEAR(w.sum(), 1.0, 1e-12);
    const double found = (w[0] * a + w[1] * b + w[2] * c - p).norm();
    constexpr int kSteps = 60;
    for (int i = 0; i <= kSteps; ++i) {
        for (int j = 0; i + j <= kSteps; ++j) {
            const double u = static_cast<double>(i) / kSteps;
            const double v = static_cast<double>(j) / kSteps;
            const Eigen::Vector3d q = (1 - u - v) * a + u * b + v * c;
            ASSERT_LE(found, (q - p).norm() + 1e-12);
        }
    }
}

TEST(ClosestPoint, OnATriangleIsOptimalInEveryRegion) {
    std::mt19937 generator(5);
    const Eigen::Vector3d a(0, 0, 0);
    const Eigen::Vector3d b(1, 0, 0);
    const Eigen::Vector3d c(0.3, 0.8, 0.1);
    for (int k = 0; k < 300; ++k) {
        expect_optimal(random_point(generator, 2.0), a, b, c);
    }
    // Known answers: above the face, beyond a vertex, beside an edge.
    EXPECT_TRUE(closest_point_on_triangle({0.3, 0.2, 5}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0})
                    .isApprox(Eigen::Vector3d(0.5, 0.3, 0.2)));
    EXPECT_EQ(closest_point_on_triangle({-1, -1, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}),
              Eigen::Vector3d(1, 0, 0));
    EXPECT_TRUE(closest_point_on_triangle({0.5, -2, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0})
                    .isApprox(Eigen::Vector3d(0.5, 0.5, 0)));
}

TEST(ClosestPoint, OnDegenerateTriangles) {
    std::mt19937 generator(6);
    for (int k = 0; k < 100; ++k) {
        const Eigen::Vector3d p = random_point(generator, 2.0);
        expect_optimal(p, {0, 0, 0}, {1, 1, 0}, {2, 2, 0});  // collinear
        expect_optimal(p, {0, 0, 0}, {1, 1, 0}, {0, 0, 0});  // a repeated corner
        expect_optimal(p, {1, 2, 3}, {1, 2, 3}, {1, 2, 3});  // a point
    }
}

TEST(TriangleBvh, AgreesWithABruteForceScan) {
    std::mt19937 generator(7);
    for (const TriangleMesh& mesh :
         {test::noisy_icosphere(3, 0.3), test::jittered_grid(12), test::noisy_torus(30, 12)}) {
        const TriangleBvh bvh(mesh);
        for (int k = 0; k < 200; ++k) {
            const Eigen::Vector3d query = random_point(generator, 2.0);
            double brute = std::numeric_limits<double>::infinity();
            for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
                const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)).transpose();
                const Eigen::Vector3d b = mesh.V.row(mesh.F(f, 1)).transpose();
                const Eigen::Vector3d c = mesh.V.row(mesh.F(f, 2)).transpose();
                const Eigen::Vector3d w = closest_point_on_triangle(query, a, b, c);
                brute = std::min(brute, (w[0] * a + w[1] * b + w[2] * c - query).norm());
            }
            const SurfacePoint found = bvh.closest_point(query);
            EXPECT_NEAR(found.distance, brute, 1e-12);
            const Eigen::Vector3d rebuilt =
                found.barycentric[0] * mesh.V.row(mesh.F(found.face, 0)).transpose() +
                found.barycentric[1] * mesh.V.row(mesh.F(found.face, 1)).transpose() +
                found.barycentric[2] * mesh.V.row(mesh.F(found.face, 2)).transpose();
            EXPECT_LT((rebuilt - found.point).norm(), 1e-12);
        }
    }
}

TEST(TriangleBvh, DistanceToASphereIsRadial) {
    const TriangleMesh sphere = make_icosphere(4, 1.0);
    const TriangleBvh bvh(sphere);
    // The polyhedron lies inside the unit sphere, within the sagitta of its faces (< 2e-3).
    for (const Eigen::Vector3d& query :
         {Eigen::Vector3d(0, 0, 3), Eigen::Vector3d(3, 0, 0), Eigen::Vector3d(-1, 2, 2)}) {
        const double distance = bvh.distance(query);
        EXPECT_GE(distance, 2.0 - 1e-12);
        EXPECT_LT(distance, 2.0 + 2e-3);
    }
}

TEST(TriangleBvh, RejectsBadMeshes) {
    EXPECT_THROW(TriangleBvh(TriangleMesh{}), InvalidInput);
    TriangleMesh mesh = make_icosphere(1);
    mesh.V(0, 0) = NAN;
    EXPECT_THROW((void)TriangleBvh(mesh), InvalidInput);
}

}  // namespace
}  // namespace genflow
