// SPDX-License-Identifier: MIT
#include "genflow/evaluation/reference_symmetry.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "genflow/exceptions.h"

namespace genflow {
namespace {

// 300 random points and their mirror images across a tilted plane, interleaved: point 2i + 1
// is the mirror of point 2i.
Eigen::MatrixX3d mirrored_cloud(const Eigen::Vector3d& normal, const Eigen::Vector3d& on_plane) {
    std::mt19937 generator(7);
    std::uniform_real_distribution<double> uniform(-1, 1);
    const Eigen::Vector3d n = normal.normalized();
    Eigen::MatrixX3d points(600, 3);
    for (Eigen::Index i = 0; i < 300; ++i) {
        const Eigen::Vector3d x(uniform(generator) * 2, uniform(generator), uniform(generator));
        const Eigen::Vector3d side = x + (0.2 + std::abs(n.dot(x - on_plane))) * n;
        points.row(2 * i) = side;
        points.row(2 * i + 1) = side - 2 * n.dot(side - on_plane) * n;
    }
    return points;
}

TEST(ReferenceSymmetry, FindsTheMirrorOfEveryPointOnTheMostSymmetricShape) {
    const Eigen::MatrixX3d symmetric =
        mirrored_cloud(Eigen::Vector3d(1, 0.2, -0.1), Eigen::Vector3d(0.3, 0, 0));
    // A second shape: the same points with every other one moved off its mirror.
    Eigen::MatrixX3d broken = symmetric;
    for (Eigen::Index i = 0; i < broken.rows(); i += 2) {
        broken(i, 1) += 0.3;
    }
    const ReferenceSymmetry symmetry = estimate_reference_symmetry({broken, symmetric}, {1.0, 1.0});
    ASSERT_TRUE(symmetry.found());
    EXPECT_EQ(symmetry.shape, 1);
    EXPECT_LT(symmetry.residual, 1e-9);
    for (Eigen::Index k = 0; k < symmetric.rows(); ++k) {
        EXPECT_EQ(symmetry.mirror[static_cast<std::size_t>(k)], k ^ 1) << k;
    }
}

TEST(ReferenceSymmetry, AShapeWithoutAMirrorPlaneHasNone) {
    std::mt19937 generator(3);
    std::uniform_real_distribution<double> uniform(0, 1);
    // Points on a spiral cone: no plane maps them onto themselves.
    Eigen::MatrixX3d spiral(400, 3);
    for (Eigen::Index i = 0; i < spiral.rows(); ++i) {
        const double t = 6 * M_PI * static_cast<double>(i) / 400;
        spiral.row(i) << t * std::cos(t), t * std::sin(t), t + 0.01 * uniform(generator);
    }
    const ReferenceSymmetry symmetry = estimate_reference_symmetry({spiral}, {10.0});
    EXPECT_FALSE(symmetry.found());
    EXPECT_GT(symmetry.residual, kSymmetryTolerance);
}

TEST(ReferenceSymmetry, RefusesShapesWithDifferentReferencePoints) {
    const Eigen::MatrixX3d points = Eigen::MatrixX3d::Random(10, 3);
    EXPECT_THROW((void)estimate_reference_symmetry({}, {}), InvalidInput);
    EXPECT_THROW((void)estimate_reference_symmetry({points, points.topRows(9)}, {1, 1}),
                 InvalidInput);
    EXPECT_THROW((void)estimate_reference_symmetry({points}, {0.0}), InvalidInput);
}

}  // namespace
}  // namespace genflow
