// SPDX-License-Identifier: MIT
#include "matching/intrinsic_start.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "genflow/mesh/primitives.h"
#include "genflow/operators/area.h"
#include "genflow/operators/mesh_size.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

TEST(IntrinsicStart, PlacesAPosedFigureWhereItBelongs) {
    const test::PosedSpikedFigure figure;
    const std::optional<detail::IntrinsicStart> start =
        detail::intrinsic_start(figure.template_mesh, figure.target);
    ASSERT_TRUE(start.has_value());
    EXPECT_GE(start->landmarks, 4);  // the legs' tips bent away from each other: 4 of 5 agree
    EXPECT_GT(start->orientation, 0.5);
    // 3.4 % (without the turning functions, 6.3 %: parts of the map follow the reflection).
    EXPECT_LT(figure.mean_distance(start->placement), 0.045);
    // The similarity recovers the motion: the sphere in the middle lands on its place.
    const Eigen::MatrixX3d placed = start->similarity.apply(figure.template_mesh.V);
    double core = 0;
    int count = 0;
    for (Eigen::Index i = 0; i < placed.rows(); ++i) {
        if (figure.template_mesh.V.row(i).norm() < 1.05) {
            core += (placed.row(i) - figure.truth.row(i)).norm();
            ++count;
        }
    }
    EXPECT_LT(core / count / bounding_box_diagonal(figure.target), 0.05);
    // The scale is the areas' (bending keeps them; these bends stretch the target by 8 %), not
    // the least-squares similarity's, which shrinks the template to fit a pose folded onto
    // itself: 2.38 here, 0.52 of TOSCA michael's size kneeling.
    const double area_scale =
        std::sqrt(surface_area(figure.target) / surface_area(figure.template_mesh));
    EXPECT_NEAR(start->similarity.scale, area_scale, 0.01 * area_scale);
    EXPECT_NEAR(start->similarity.scale, figure.motion.scale, 0.05 * figure.motion.scale);
}

// The next landmark sets' starts come after the preferred one, each from another set: the
// figure's spikes matched otherwise put the template elsewhere. They come by how well their
// maps keep the orientation, none by more than the margin better than the preferred one's
// (which is the most consistent set within it).
TEST(IntrinsicStart, RanksTheOtherLandmarkSetsAfterThePreferredOne) {
    const test::PosedSpikedFigure figure;
    const std::optional<detail::IntrinsicStart> preferred =
        detail::intrinsic_start(figure.template_mesh, figure.target);
    const std::vector<detail::IntrinsicStart> starts =
        detail::intrinsic_starts(figure.template_mesh, figure.target, 4);
    ASSERT_TRUE(preferred.has_value());
    ASSERT_GE(starts.size(), 2U);
    EXPECT_LE(starts.size(), 4U);
    EXPECT_EQ(starts.front().placement, preferred->placement);
    for (std::size_t k = 1; k < starts.size(); ++k) {
        EXPECT_GT(figure.mean_distance(starts[k].placement),
                  figure.mean_distance(preferred->placement))
            << k;
        EXPECT_LE(starts[k].orientation, starts.front().orientation + 0.1) << k;
        if (k > 1) {
            EXPECT_LE(starts[k].orientation, starts[k - 1].orientation) << k;
        }
    }
    EXPECT_TRUE(detail::intrinsic_starts(figure.template_mesh, figure.target, 0).empty());
}

}  // namespace
}  // namespace genflow
