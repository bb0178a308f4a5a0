// SPDX-License-Identifier: MIT
#include "genflow/evaluation/single_view.h"

#include <gtest/gtest.h>

#include <array>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/area.h"
#include "genflow/operators/normals.h"

namespace genflow {
namespace {

// Looking down on a sphere: the faces turned up, half the area, every vertex kept in order.
TEST(SingleView, KeepsTheFacesThatFaceTheCamera) {
    const TriangleMesh sphere = make_icosphere(3);
    const TriangleMesh seen = single_view(sphere, Eigen::Vector3d(0, 0, -2));
    EXPECT_EQ(seen.V, sphere.V);
    EXPECT_TRUE((face_normals(seen).col(2).array() > 0).all());
    EXPECT_NEAR(surface_area(seen), surface_area(sphere) / 2, 0.02 * surface_area(sphere));
    Eigen::Index up = 0;
    const Eigen::MatrixX3d normals = face_normals(sphere);
    for (Eigen::Index f = 0; f < normals.rows(); ++f) {
        up += normals(f, 2) > 0 ? 1 : 0;
    }
    EXPECT_EQ(seen.F.rows(), up);
    EXPECT_THROW((void)single_view(sphere, Eigen::Vector3d::Zero()), InvalidInput);
    EXPECT_THROW((void)single_view(sphere, Eigen::Vector3d(NAN, 0, 1)), InvalidInput);
}

// Unit directions, the same for a seed, spread over the sphere: their mean over many seeds is
// near the origin (1/√n ≈ 0.03 for n = 1000 in each coordinate) and every octant is visited.
TEST(SingleView, DirectionsAreUniformOnTheSphereAndRepeatable) {
    EXPECT_EQ(view_direction(7), view_direction(7));
    EXPECT_NE(view_direction(7), view_direction(8));
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    std::array<int, 8> octants{};
    for (std::uint64_t seed = 0; seed < 1000; ++seed) {
        const Eigen::Vector3d d = view_direction(seed);
        EXPECT_NEAR(d.norm(), 1, 1e-12);
        mean += d / 1000;
        ++octants[static_cast<std::size_t>((d.x() > 0) + 2 * (d.y() > 0) + 4 * (d.z() > 0))];
    }
    EXPECT_LT(mean.norm(), 0.1);
    for (const int count : octants) {
        EXPECT_GT(count, 80);  // 125 expected
    }
}

}  // namespace
}  // namespace genflow
