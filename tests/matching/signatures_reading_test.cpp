// SPDX-License-Identifier: MIT
// The judge of the two readings (signatures_reading.h): its scores of a right and a mirrored
// map (its rule, keeps_signatures_reading(), is tested with the others in selection_test.cpp).
#include "matching/signatures_reading.h"

#include <gtest/gtest.h>

#include "matching/finest_bases.h"
#include "support/test_meshes.h"

namespace genflow::detail {
namespace {

// On the posed figure, the template laid where it belongs and laid on its own mirror image:
// both maps are isometries, so both commute with the Laplacians alike (to rounding), and only
// the orientation tells them apart: the mirrored map reverses it.
TEST(ReadingJudge, ScoresTheRightMapAndItsMirrorImage) {
    const test::PosedSpikedFigure figure;
    const std::optional<FinestBases> bases = finest_bases(figure.template_mesh, figure.target);
    ASSERT_TRUE(bases.has_value());
    const ReadingJudge judge(*bases, figure.template_mesh, figure.target, true);
    const ReadingScore right = judge.score(figure.truth);
    const ReadingScore mirrored =
        judge.score(figure.truth(test::figure_mirror(figure.template_mesh), Eigen::all));
    ASSERT_TRUE(right.orientation_ratio.has_value());
    ASSERT_TRUE(mirrored.orientation_ratio.has_value());
    std::printf("right: commutativity %.4f, orientation %.3f; mirrored: %.4f, %.3f\n",
                right.commutativity, *right.orientation_ratio, mirrored.commutativity,
                *mirrored.orientation_ratio);
    EXPECT_LT(right.commutativity, 0.1);
    EXPECT_NEAR(mirrored.commutativity, right.commutativity, 1e-3 * right.commutativity);
    EXPECT_LT(*right.orientation_ratio, 1);
    EXPECT_GT(*mirrored.orientation_ratio, 1);
}

// Unasked, the judge leaves out the orientation (two eigen-solves of the whole meshes) and
// scores the commutativity alone, the same as with it.
TEST(ReadingJudge, ScoresTheCommutativityAloneUnlessAskedForTheOrientation) {
    const test::PosedSpikedFigure figure;
    const std::optional<FinestBases> bases = finest_bases(figure.template_mesh, figure.target);
    ASSERT_TRUE(bases.has_value());
    const ReadingScore with =
        ReadingJudge(*bases, figure.template_mesh, figure.target, true).score(figure.truth);
    const ReadingScore without =
        ReadingJudge(*bases, figure.template_mesh, figure.target, false).score(figure.truth);
    EXPECT_TRUE(with.orientation_ratio.has_value());
    EXPECT_FALSE(without.orientation_ratio.has_value());
    EXPECT_EQ(without.commutativity, with.commutativity);
}

}  // namespace
}  // namespace genflow::detail
