// SPDX-License-Identifier: MIT
#include "matching/swapped_limbs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "genflow/exceptions.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// The spiked figure is symmetric left for right (x → −x): its head, two arms and two legs
// (tests/support/test_meshes.cpp). A placement on another sampling of it that puts each leg on
// the other one (each point on its mirror image), the rest where it belongs.
struct SwappedLegs {
    TriangleMesh template_mesh = test::spiked_figure(3, 0);
    TriangleMesh target = test::spiked_figure(4, 7);
    detail::IntrinsicShape from = detail::analyse_intrinsic_shape(template_mesh);
    detail::IntrinsicShape to = detail::analyse_intrinsic_shape(target);

    // The figure's legs point down (z < 0), one to each side.
    static bool on_a_leg(const Eigen::RowVector3d& point) {
        return point.z() < -1.2 && std::abs(point.x()) > 0.3;
    }
    [[nodiscard]] Eigen::MatrixX3d placement(bool swapped) const {
        Eigen::MatrixX3d placed = from.coarse.mesh.V;
        for (Eigen::Index v = 0; v < placed.rows(); ++v) {
            if (swapped && on_a_leg(placed.row(v))) {
                placed(v, 0) = -placed(v, 0);
            }
        }
        return placed;
    }
    [[nodiscard]] detail::LimbPlacement placed(bool swapped) const {
        return detail::place_limbs(from, to, placement(swapped));
    }
    // The template extremities at the legs' tips.
    [[nodiscard]] std::vector<std::size_t> leg_tips() const {
        std::vector<std::size_t> tips;
        for (std::size_t k = 0; k < from.extremities.size(); ++k) {
            if (on_a_leg(from.coarse.mesh.V.row(from.extremities[k]))) {
                tips.push_back(k);
            }
        }
        return tips;
    }
};

TEST(SwappedLimbs, KeepsAMatchThatPutsEveryLimbInItsPlace) {
    const SwappedLegs figure;
    ASSERT_EQ(figure.from.extremities.size(), 5U);  // head, arms, legs
    const detail::SwappedLimbs found =
        detail::find_swapped_limbs(figure.from, figure.to, figure.placed(false), 0);
    EXPECT_TRUE(found.exchanged.empty());
    // Another sampling, so not 1; every pair's functions agree closely.
    EXPECT_GT(found.agreement_before, 0.9);
    EXPECT_EQ(found.agreement_after, found.agreement_before);
}

TEST(SwappedLimbs, ExchangesTheLegsAMatchPutOnEachOther) {
    const SwappedLegs figure;
    const std::vector<std::size_t> tips = figure.leg_tips();
    ASSERT_EQ(tips.size(), 2U);
    const double kept = detail::find_swapped_limbs(figure.from, figure.to, figure.placed(false), 0)
                            .agreement_before;
    const detail::SwappedLimbs found =
        detail::find_swapped_limbs(figure.from, figure.to, figure.placed(true), 0.05);
    ASSERT_EQ(found.exchanged.size(), 1U);
    EXPECT_EQ(std::min(found.exchanged[0].first, found.exchanged[0].second), tips[0]);
    EXPECT_EQ(std::max(found.exchanged[0].first, found.exchanged[0].second), tips[1]);
    // The 7 pairs with a leg's tip disagree (of 10), the pair of both legs reversed.
    EXPECT_LT(found.agreement_before, 0.5);
    EXPECT_GT(found.agreement_after, found.agreement_before + 0.3);
    // Each leg's tip now belongs on the leg the match put it on.
    for (const std::size_t tip : tips) {
        const Eigen::RowVector3d from_tip =
            figure.from.coarse.mesh.V.row(figure.from.extremities[tip]);
        const Eigen::RowVector3d image = figure.to.coarse.mesh.V.row(found.images[tip]);
        EXPECT_LT((image - from_tip).norm(), 0.3) << tip;
    }
    EXPECT_LT(found.agreement_after, kept + 0.3);  // not better than no swap at all
}

TEST(SwappedLimbs, AMarginAboveTheGainExchangesNothing) {
    const SwappedLegs figure;
    const detail::SwappedLimbs found =
        detail::find_swapped_limbs(figure.from, figure.to, figure.placed(true), 2);
    EXPECT_TRUE(found.exchanged.empty());
    EXPECT_EQ(found.agreement_after, found.agreement_before);
}

TEST(SwappedLimbs, ExchangesNothingThatLeavesTheMapAgreeingPoorly) {
    const SwappedLegs figure;
    const detail::SwappedLimbs found =
        detail::find_swapped_limbs(figure.from, figure.to, figure.placed(true), 0.05, 0.99);
    EXPECT_TRUE(found.exchanged.empty());
    EXPECT_EQ(found.images, figure.placed(true).images);
    EXPECT_EQ(found.agreement_after, found.agreement_before);
}

// A match that keeps the exchanges has not drifted from them; the one that put the legs back
// has, by about the distance between the legs' tips.
TEST(SwappedLimbs, TellsWhetherAMatchKeptTheExchanges) {
    const SwappedLegs figure;
    const detail::SwappedLimbs found =
        detail::find_swapped_limbs(figure.from, figure.to, figure.placed(true), 0.05);
    ASSERT_EQ(found.exchanged.size(), 1U);
    EXPECT_LT(detail::exchange_drift(figure.to, found, figure.placed(false)), 0.05);
    const auto [a, b] = found.exchanged[0];
    const double between = figure.to.distance(found.images[a], found.images[b]);
    EXPECT_NEAR(detail::exchange_drift(figure.to, found, figure.placed(true)), between,
                0.05 * between);
}

// The placement by the map of the exchanged extremities puts each leg where it belongs: every
// template vertex of a leg (at rest, the target is the same figure) near its own place, none
// near the other leg; nothing when nothing was exchanged.
TEST(SwappedLimbs, PlacesTheExchangedLimbsWhereTheyBelong) {
    const SwappedLegs figure;
    const detail::SwappedLimbs found =
        detail::find_swapped_limbs(figure.from, figure.to, figure.placed(true), 0.05);
    ASSERT_EQ(found.exchanged.size(), 1U);
    const std::optional<Eigen::MatrixX3d> placement =
        detail::exchanged_placement(figure.template_mesh, figure.from, figure.to, found);
    ASSERT_TRUE(placement.has_value());
    ASSERT_EQ(placement->rows(), figure.template_mesh.V.rows());
    int legs = 0;
    for (Eigen::Index v = 0; v < placement->rows(); ++v) {
        const Eigen::RowVector3d rest = figure.template_mesh.V.row(v);
        if (SwappedLegs::on_a_leg(rest)) {
            ++legs;
            Eigen::RowVector3d mirrored = rest;
            mirrored.x() = -mirrored.x();
            const double own = (placement->row(v) - rest).norm();
            EXPECT_LT(own, 0.5 * (placement->row(v) - mirrored).norm()) << v;
        }
    }
    EXPECT_GT(legs, 10);
    EXPECT_FALSE(detail::exchanged_placement(
                     figure.template_mesh, figure.from, figure.to,
                     detail::find_swapped_limbs(figure.from, figure.to, figure.placed(false), 0))
                     .has_value());
}

TEST(SwappedLimbs, RefusesPlacementsOfAnotherSize) {
    const SwappedLegs figure;
    EXPECT_THROW((void)detail::place_limbs(figure.from, figure.to, Eigen::MatrixX3d::Zero(3, 3)),
                 InvalidInput);
}

// A match that lays the whole figure on its mirror image (x → −x, which the symmetric figure
// fits as well as itself) reverses every pair's turning function: the agreement falls below
// zero, which is how a fit to a mirrored map is told (detail::keeps_fit()).
TEST(SwappedLimbs, AMirroredMatchAgreesNegatively) {
    const SwappedLegs figure;
    Eigen::MatrixX3d mirrored = figure.from.coarse.mesh.V;
    mirrored.col(0) = -mirrored.col(0);
    EXPECT_LT(detail::place_limbs(figure.from, figure.to, mirrored).agreement, -0.5);
    EXPECT_GT(figure.placed(false).agreement, 0.5);
}

// The agreement of a map with itself: every pair's functions are its own, correlation 1.
TEST(SwappedLimbs, AShapeAgreesWithItself) {
    const SwappedLegs figure;
    std::vector<Eigen::Index> identity(static_cast<std::size_t>(figure.from.coarse.mesh.V.rows()));
    for (std::size_t v = 0; v < identity.size(); ++v) {
        identity[v] = static_cast<Eigen::Index>(v);
    }
    EXPECT_NEAR(
        detail::turning_agreement(figure.from, figure.from, identity, figure.from.extremities), 1.0,
        1e-12);
}

// n · (∇d_a × ∇d_b) changes sign with the pair's order, as under a reflection.
TEST(SwappedLimbs, TurningFunctionsChangeSignWithThePairsOrder) {
    const SwappedLegs figure;
    const Eigen::Index a = figure.from.extremities[1];
    const Eigen::Index b = figure.from.extremities[3];
    const Eigen::MatrixXd ab = detail::turning_functions(figure.from, {a, b});
    const Eigen::MatrixXd ba = detail::turning_functions(figure.from, {b, a});
    ASSERT_EQ(ab.cols(), 1);
    EXPECT_LT((ab + ba).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_GT(ab.cwiseAbs().maxCoeff(), 0.5);  // the ways to an arm and a leg cross somewhere
}

}  // namespace
}  // namespace genflow
