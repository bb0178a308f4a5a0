// SPDX-License-Identifier: MIT
#include "genflow/matching/partial_target.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "genflow/evaluation/scan_defects.h"
#include "genflow/evaluation/single_view.h"
#include "genflow/exceptions.h"
#include "genflow/matching/match.h"
#include "genflow/matching/rigid_alignment.h"
#include "genflow/mesh/face_selection.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/area.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/normals.h"
#include "genflow/operators/volume.h"
#include "genflow/spatial/point_cloud_surface.h"
#include "matching/partial_target.h"
#include "matching/similarity_scale.h"

namespace genflow {
namespace {

// The limb bent at its elbow, and where each vertex of the unbent template belongs on it.
struct ViewedLimb {
    TriangleMesh template_mesh = make_limb(3);
    TriangleMesh target = make_limb(4, 9);
    Eigen::MatrixX3d truth;
    ViewedLimb() {
        const std::vector<Joint> bend{
            {{1.0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 35 * std::numbers::pi / 180, 0.4}};
        target.V = bend_at_joints(target.V, bend);
        truth = bend_at_joints(template_mesh.V, bend);
    }
    // Mean distance from the truth over the target's diagonal, of the vertices `seen` marks.
    [[nodiscard]] double error(const Eigen::MatrixX3d& positions,
                               const std::vector<bool>& seen) const {
        double sum = 0;
        int count = 0;
        for (Eigen::Index i = 0; i < positions.rows(); ++i) {
            if (seen[static_cast<std::size_t>(i)]) {
                sum += (positions.row(i) - truth.row(i)).norm();
                ++count;
            }
        }
        return sum / count / bounding_box_diagonal(target);
    }
};

// The template vertices whose place on the target faces a camera looking along `view`.
std::vector<bool> seen_template_vertices(const ViewedLimb& limb, const Eigen::Vector3d& view) {
    const TriangleMesh placed{limb.truth, limb.template_mesh.F};
    const TriangleMesh seen = single_view(placed, view);
    std::vector<bool> marked(static_cast<std::size_t>(placed.V.rows()), false);
    for (Eigen::Index f = 0; f < seen.F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            marked[static_cast<std::size_t>(seen.F(f, c))] = true;
        }
    }
    return marked;
}

TEST(PartialTarget, NamesEachExtent) {
    for (const TargetExtent extent :
         {TargetExtent::Automatic, TargetExtent::Complete, TargetExtent::Partial}) {
        EXPECT_EQ(parse_target_extent(to_string(extent)), extent);
    }
    EXPECT_FALSE(parse_target_extent("half").has_value());
}

// One side of a sphere leaves a hole of πr² beside its 2πr², a third of the closed surface:
// partial, at any scale, ragged or not. The whole sphere is not, neither is the one side against
// a template that is itself that open, and neither is the sphere with ten holes of 0.03
// diagonals: their rims are long, 2.0 per √area against the side's 3.1, but close with 3 %;
// nor is the surface made on a shape's points.
TEST(PartialTarget, FindsOneSideOfAShapeButNotTheWholeAtAnyScale) {
    const TriangleMesh sphere = make_icosphere(3);
    TriangleMesh side = single_view(sphere, Eigen::Vector3d(0.2, -1, 0.3));
    EXPECT_TRUE(shows_part_only(sphere, side));
    EXPECT_FALSE(shows_part_only(sphere, sphere));
    EXPECT_FALSE(shows_part_only(side, side));
    side.V *= 1000;
    EXPECT_TRUE(shows_part_only(sphere, side));
    EXPECT_TRUE(
        shows_part_only(sphere, with_scan_defects(side, ScanDefects{.ragged_boundary = true}, 1)));
    const TriangleMesh holed = with_scan_defects(make_icosphere(4), ScanDefects{.holes = 10}, 2);
    EXPECT_GT(detail::boundary_length(holed) / std::sqrt(surface_area(holed)), 1.5);
    EXPECT_FALSE(shows_part_only(sphere, holed));
    // The surface made on a shape's points has many small holes where the fans disagree, with
    // rims 7.7 per √area on the limb: complete, as the whole shape is.
    const TriangleMesh limb = make_limb(3);
    const TriangleMesh on_points = point_cloud_surface(limb.V, Eigen::MatrixX3d(0, 3));
    EXPECT_GT(detail::boundary_length(on_points) / std::sqrt(surface_area(on_points)), 1.5);
    EXPECT_FALSE(shows_part_only(limb, on_points));
    TriangleMesh point = sphere;
    point.V.setZero();
    EXPECT_THROW((void)shows_part_only(sphere, point), InvalidInput);
}

// A depth camera's view of a sphere, its points with noise of half a mean edge and their
// normals: the surface made on them is partial, as the view is; the whole sphere's points with
// the same noise are not (docs/benchmarks.md, "Holes that touch the rim").
TEST(PartialTarget, FindsANoisyViewGivenAsPoints) {
    const TriangleMesh sphere = make_icosphere(4);
    const Eigen::MatrixX3d normals = vertex_normals(sphere);
    const std::vector<Eigen::Index> seen =
        vertices_used_by(single_view(sphere, Eigen::Vector3d(0.2, -1, 0.3)).F, sphere.V.rows());
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        const Eigen::MatrixX3d noisy = add_noise(sphere, 0.5 * mean_edge_length(sphere), seed).V;
        EXPECT_TRUE(shows_part_only(
            sphere, point_cloud_surface(noisy(seen, Eigen::all), normals(seen, Eigen::all))))
            << seed;
        EXPECT_FALSE(shows_part_only(sphere, point_cloud_surface(noisy, normals))) << seed;
    }
}

// Onto one side of the limb, turned and moved, the one-sided rigid alignment at the template's
// scale places the template where it belongs; the two-sided one, scaled by the areas' ratio,
// shrinks it to the side's area.
TEST(PartialTarget, RigidAlignmentOneSidedPlacesTheTemplateOnAView) {
    const TriangleMesh moving = make_limb(3);
    Similarity truth;
    truth.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 0.5).normalized()).matrix();
    truth.translation = Eigen::Vector3d(0.5, -2, 1);
    TriangleMesh whole = make_limb(4, 11);
    whole.V = truth.apply(whole.V);
    const TriangleMesh view = single_view(whole, Eigen::Vector3d(0.3, 0.2, -1));
    const double diagonal = bounding_box_diagonal(whole);
    const auto error = [&](const Similarity& found) {
        return (found.apply(moving.V) - truth.apply(moving.V)).rowwise().norm().mean() / diagonal;
    };
    const RigidAlignment one_sided =
        align_rigidly(moving, view, {.allow_scaling = false, .moving_coverage = 0});
    const RigidAlignment two_sided = align_rigidly(moving, view);
    std::printf("one-sided %.4f, two-sided %.4f (scale %.3f)\n", error(one_sided.transform),
                error(two_sided.transform), two_sided.transform.scale);
    EXPECT_LT(error(one_sided.transform), 0.02);
    EXPECT_DOUBLE_EQ(one_sided.transform.scale, 1);
    EXPECT_LT(two_sided.transform.scale, 0.85);
    EXPECT_THROW((void)align_rigidly(moving, view, {.moving_coverage = 1.5}), InvalidInput);
}

// A view of the bent limb, matched as a partial target: the template covers the view without
// its unseen side being pulled onto it, so it keeps its volume and ends nearer the truth, seen
// and unseen, than matched as a complete target, which flattens it onto the view.
TEST(PartialTarget, MatchesAViewWithoutPullingTheUnseenSideOntoIt) {
    const ViewedLimb limb;
    const Eigen::Vector3d camera(0.2, 0.3, -1);
    const TriangleMesh view = single_view(limb.target, camera);
    MatchOptions options = paper_match_options();
    const MatchResult partial = match(limb.template_mesh, view, options);
    options.partial.extent = TargetExtent::Complete;
    const MatchResult complete = match(limb.template_mesh, view, options);
    EXPECT_TRUE(partial.partial_target);
    EXPECT_FALSE(complete.partial_target);
    const std::vector<bool> seen = seen_template_vertices(limb, camera);
    const std::vector<bool> all(seen.size(), true);
    const double volume = enclosed_volume(limb.template_mesh);
    std::printf("seen %.4f / %.4f, all %.4f / %.4f, volume %.3f / %.3f of the template's\n",
                limb.error(partial.deformed.V, seen), limb.error(complete.deformed.V, seen),
                limb.error(partial.deformed.V, all), limb.error(complete.deformed.V, all),
                enclosed_volume(partial.deformed) / volume,
                enclosed_volume(complete.deformed) / volume);
    EXPECT_LT(limb.error(partial.deformed.V, seen), limb.error(complete.deformed.V, seen));
    EXPECT_LT(limb.error(partial.deformed.V, all), 0.7 * limb.error(complete.deformed.V, all));
    EXPECT_GT(enclosed_volume(partial.deformed), 0.8 * volume);   // measured 0.86
    EXPECT_LT(enclosed_volume(complete.deformed), 0.1 * volume);  // 0.01
}

// A view of the limb from above (its faces turned up), and two starts: the template where it
// belongs, and moved up until its underside lies on the view. Both bring every point of the view
// near the template; only the first shows the view the template's side that faces the same way,
// and the facing distance ranks it first whichever order the starts come in.
TEST(PartialTarget, RanksFirstTheStartThatFacesTheView) {
    const TriangleMesh shape = make_limb(3);
    const TriangleMesh view = single_view(make_limb(4, 9), Eigen::Vector3d(0, 0, -1));
    const Eigen::VectorXd heights = shape.V.col(2);
    Similarity above;
    above.translation.z() = heights.maxCoeff() - heights.minCoeff();
    const Similarity right;
    for (const bool right_first : {false, true}) {
        std::vector<Similarity> starts{right_first ? right : above, right_first ? above : right};
        detail::rank_by_facing_distance(starts, shape, view, MatchOptions{});
        EXPECT_EQ(starts.front().translation, right.translation) << right_first;
    }
}

}  // namespace
}  // namespace genflow
