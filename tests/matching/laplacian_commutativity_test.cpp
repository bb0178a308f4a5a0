// SPDX-License-Identifier: MIT
#include "genflow/matching/laplacian_commutativity.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include "genflow/exceptions.h"
#include "genflow/matching/correspondence.h"
#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

constexpr Eigen::Index kFunctions = kCommutativityFunctions;

// The limb's +x end bent by 90° at x = 1 (an isometry, up to the blend).
Eigen::MatrixX3d bent(const Eigen::MatrixX3d& points) {
    return bend_at_joints(points, {Joint{.centre = Eigen::Vector3d(1, 0, 0),
                                         .direction = Eigen::Vector3d::UnitX(),
                                         .axis = Eigen::Vector3d::UnitZ(),
                                         .angle = std::numbers::pi / 2,
                                         .width = 0.3}});
}

struct Surface {
    TriangleMesh mesh;
    LaplacianEigenbasis basis = laplacian_eigenbasis(mesh, kFunctions + 1);
};

// Every vertex of a surface on itself.
TEST(LaplacianCommutativity, IdentityCommutes) {
    const Surface limb{make_limb(3)};
    const double score = laplacian_commutativity(limb.basis, limb.mesh, limb.basis,
                                                 closest_points(limb.mesh.V, limb.mesh));
    EXPECT_LT(score, 1e-10);
}

// λ·area does not change with the size: a copy three times as large commutes with the original
// (with λ alone the score would be (1 − 1/9)²).
TEST(LaplacianCommutativity, DoesNotDependOnTheSurfacesSizes) {
    const Surface limb{make_limb(3)};
    TriangleMesh large = limb.mesh;
    large.V *= 3;
    const Surface copy{large};
    const double score =
        laplacian_commutativity(limb.basis, copy.mesh, copy.basis, closest_points(large.V, large));
    EXPECT_LT(score, 1e-8);
}

// A template sampled apart from its target and bent as the target is: the right placement's
// map nearly commutes; the same placement turned end for end (its hump on the target's other
// end) commutes less by several times (the hump is the only difference between its ends).
TEST(LaplacianCommutativity, TellsARightMapFromAWrongOne) {
    const Surface from{make_limb(4)};
    TriangleMesh target = make_limb(4, 7);
    target.V = bent(target.V);
    const Surface to{target};
    const double right = laplacian_commutativity(from.basis, to.mesh, to.basis,
                                                 closest_points(bent(from.mesh.V), target));
    Eigen::MatrixX3d turned = from.mesh.V;
    turned.col(0) *= -1;
    turned.col(1) *= -1;
    const double wrong = laplacian_commutativity(from.basis, to.mesh, to.basis,
                                                 closest_points(bent(turned), target));
    std::printf("commutativity: right map %.4f, turned end for end %.4f\n", right, wrong);
    EXPECT_LT(right, 0.05);
    EXPECT_GT(wrong, 4 * right);
}

// A map that puts every vertex on one point pulls every function back to 0.
TEST(LaplacianCommutativity, MapOntoOnePointScoresOne) {
    const Surface limb{make_limb(3)};
    const SurfacePoint corner{.face = 0,
                              .barycentric = Eigen::Vector3d(1, 0, 0),
                              .point = limb.mesh.V.row(limb.mesh.F(0, 0)).transpose(),
                              .distance = 0};
    const std::vector<SurfacePoint> one_point(static_cast<std::size_t>(limb.mesh.V.rows()), corner);
    EXPECT_EQ(laplacian_commutativity(limb.basis, limb.mesh, limb.basis, one_point), 1.0);
}

TEST(LaplacianCommutativity, RejectsInconsistentInputs) {
    const Surface limb{make_limb(3)};
    const std::vector<SurfacePoint> map = closest_points(limb.mesh.V, limb.mesh);
    EXPECT_THROW(
        (void)laplacian_commutativity(limb.basis, limb.mesh, limb.basis, map, kFunctions + 1),
        InvalidInput);
    EXPECT_THROW((void)laplacian_commutativity(limb.basis, limb.mesh, limb.basis, map, 0),
                 InvalidInput);
    EXPECT_THROW((void)laplacian_commutativity(limb.basis, limb.mesh, limb.basis,
                                               {map.begin(), map.end() - 1}),
                 InvalidInput);
    std::vector<SurfacePoint> off_surface = map;
    off_surface.back().face = limb.mesh.F.rows();
    EXPECT_THROW((void)laplacian_commutativity(limb.basis, limb.mesh, limb.basis, off_surface),
                 InvalidInput);
}

}  // namespace
}  // namespace genflow
