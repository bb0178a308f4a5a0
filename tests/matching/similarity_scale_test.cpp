// SPDX-License-Identifier: MIT
// The starts' scale: from the areas, unless a rough surface makes them mislead
// (similarity_scale.h).
#include "matching/similarity_scale.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "genflow/matching/rigid_alignment.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/area.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/volume.h"
#include "matching/intrinsic_start.h"

namespace genflow {
namespace {

// The generated limb (2562 vertices) sampled elsewhere, turned and scaled by `scale`, with
// Gaussian noise of `noise` times its bounding-box diagonal on every coordinate.
TriangleMesh scaled_limb(double scale, double noise) {
    TriangleMesh limb = make_limb(4, 7);
    limb.V = scale * limb.V *
             Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 0).normalized()).toRotationMatrix();
    return noise > 0 ? add_noise(limb, noise * bounding_box_diagonal(limb), 11) : limb;
}

// The icosphere without the faces of its top cap, and the same moved: its capped volume is the
// volume of the sphere cut by the cap's plane (at most the sphere's), wherever it lies; the
// plain enclosed volume is not a volume there and changes with the origin.
TEST(SimilarityScale, CappedVolumeOfAnOpenSphereDoesNotDependOnWhereItLies) {
    const TriangleMesh sphere = make_icosphere(4);
    EXPECT_NEAR(detail::capped_volume(sphere), enclosed_volume(sphere), 1e-12);
    EXPECT_EQ(detail::boundary_length(sphere), 0);
    TriangleMesh open = sphere;
    Eigen::Index kept = 0;
    for (Eigen::Index f = 0; f < sphere.F.rows(); ++f) {
        const double top = std::min({sphere.V(sphere.F(f, 0), 2), sphere.V(sphere.F(f, 1), 2),
                                     sphere.V(sphere.F(f, 2), 2)});
        if (top < 0.8) {
            open.F.row(kept++) = sphere.F.row(f);
        }
    }
    open.F.conservativeResize(kept, 3);
    const double capped = detail::capped_volume(open);
    EXPECT_GT(detail::boundary_length(open), 3.0);  // a circle of radius ≈ 0.6
    EXPECT_LT(capped, enclosed_volume(sphere));
    EXPECT_GT(capped, 0.95 * enclosed_volume(sphere));
    TriangleMesh moved = open;
    moved.V.rowwise() += Eigen::RowVector3d(3, -5, 40);
    EXPECT_NEAR(detail::capped_volume(moved), capped, 1e-9);
    EXPECT_GT(std::abs(enclosed_volume(moved) - capped), 1.0);
}

// A target rough with noise of 0.5 % of its diagonal has more area than its shape: the areas'
// scale is too large, and the volumes' is right (within 1 %).
TEST(SimilarityScale, RoughTargetGetsTheVolumesScale) {
    const TriangleMesh template_mesh = make_limb(4);
    const TriangleMesh target = scaled_limb(1.7, 0.005);
    const double area_scale = std::sqrt(surface_area(target) / surface_area(template_mesh));
    std::printf("area scale %.4f (1.7 true)\n", area_scale);
    EXPECT_GT(area_scale, 1.7 * (1 + detail::kAreaVolumeTolerance));
    const auto scale = detail::volume_scale_where_areas_mislead(template_mesh, target, area_scale);
    ASSERT_TRUE(scale.has_value());
    EXPECT_NEAR(*scale, 1.7, 0.017);
    // A rough template: the areas' scale is too small.
    const auto back =
        detail::volume_scale_where_areas_mislead(target, template_mesh, 1 / area_scale);
    ASSERT_TRUE(back.has_value());
    EXPECT_NEAR(*back, 1 / 1.7, 0.01 / 1.7);
}

// Clean, another sampling: the areas' scale stands. Rough but open along a long boundary (the
// limb cut lengthwise through its middle: 5.8·√area), the capped volume is no longer the shape's:
// the areas' scale stands too.
TEST(SimilarityScale, CleanTargetOrLongBoundaryKeepsTheAreasScale) {
    const TriangleMesh template_mesh = make_limb(4);
    const TriangleMesh clean = scaled_limb(1.7, 0);
    EXPECT_FALSE(
        detail::volume_scale_where_areas_mislead(
            template_mesh, clean, std::sqrt(surface_area(clean) / surface_area(template_mesh)))
            .has_value());
    TriangleMesh half = scaled_limb(1.7, 0.005);
    Eigen::Index kept = 0;
    const Eigen::RowVector3d centre = half.V.colwise().mean();
    const Eigen::RowVector3d across = half.V.row(0) - centre;  // any direction through it
    for (Eigen::Index f = 0; f < half.F.rows(); ++f) {
        if ((half.V.row(half.F(f, 0)) - centre).dot(across) > 0) {
            half.F.row(kept++) = half.F.row(f);
        }
    }
    half.F.conservativeResize(kept, 3);
    ASSERT_GT(detail::boundary_length(half),
              detail::kShortBoundary * std::sqrt(surface_area(half)));
    EXPECT_FALSE(detail::volume_scale_where_areas_mislead(template_mesh, half, 2.0).has_value());
}

// The rigid starts onto that rough target have its size: 1.7 within 1 % (the areas' scale is
// more than 5 % too large).
TEST(SimilarityScale, RigidStartsOfARoughTargetHaveItsSize) {
    const std::vector<RigidAlignment> starts =
        rigid_alignment_candidates(make_limb(4), scaled_limb(1.7, 0.005));
    ASSERT_FALSE(starts.empty());
    for (const RigidAlignment& start : starts) {
        EXPECT_NEAR(start.transform.scale, 1.7, 0.017);
    }
}

// An intrinsic start taken to another scale keeps its rotation and gets the translation that
// fits its placement best at that scale: what a least-squares fit at that scale gives (the
// rotation between centred point sets does not depend on their scales).
TEST(SimilarityScale, RescaledIntrinsicStartFitsItsPlacementAtTheNewScale) {
    const TriangleMesh template_mesh = make_limb(3);
    Similarity motion;
    motion.rotation =
        Eigen::AngleAxisd(1.1, Eigen::Vector3d(0, 1, 1).normalized()).toRotationMatrix();
    motion.scale = 2.0;
    motion.translation = Eigen::Vector3d(1, -2, 0.5);
    detail::IntrinsicStart start;
    start.placement =
        add_noise(TriangleMesh{motion.apply(template_mesh.V), template_mesh.F}, 0.05, 3).V;
    const auto fit_at = [&](double scale) {
        const Eigen::Matrix4d fit =
            Eigen::umeyama(scale * template_mesh.V.transpose(), start.placement.transpose(), false);
        Similarity similarity;
        similarity.rotation = fit.topLeftCorner<3, 3>();
        similarity.translation = fit.topRightCorner<3, 1>();
        similarity.scale = scale;
        return similarity;
    };
    start.similarity = fit_at(2.0);
    detail::rescale(start, template_mesh, 2.5);
    const Similarity expected = fit_at(2.5);
    EXPECT_EQ(start.similarity.scale, 2.5);
    EXPECT_TRUE(start.similarity.rotation.isApprox(expected.rotation, 1e-9));
    EXPECT_TRUE(start.similarity.translation.isApprox(expected.translation, 1e-9));
}

}  // namespace
}  // namespace genflow
