// SPDX-License-Identifier: MIT
// The matcher's keep-or-reject rules (selection.h), on scores given by hand.
#include "matching/selection.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <optional>

#include "genflow/matching/match.h"

namespace genflow::detail {
namespace {

Score rigid(double disagreement, double turning = 0) {
    return {StartKind::Rigid, disagreement, [turning] { return turning; }};
}

Score intrinsic(double disagreement, double turning = 0) {
    return {StartKind::Intrinsic, disagreement, [turning] { return turning; }};
}

// Between results of the same kind, or a rigid result against an intrinsic one, the lower
// disagreement wins and the turning functions are never asked.
TEST(Selection, LowerDisagreementWinsBetweenLikeStarts) {
    const auto never = [] {
        ADD_FAILURE() << "turning functions asked";
        return 0.0;
    };
    EXPECT_TRUE(replaces({StartKind::Rigid, 0.2, never}, {StartKind::Rigid, 0.3, never}));
    EXPECT_FALSE(replaces({StartKind::Rigid, 0.3, never}, {StartKind::Rigid, 0.3, never}));
    EXPECT_TRUE(replaces({StartKind::Intrinsic, 0.29, never}, {StartKind::Intrinsic, 0.3, never}));
    EXPECT_TRUE(replaces({StartKind::Rigid, 0.29, never}, {StartKind::Intrinsic, 0.3, never}));
    EXPECT_FALSE(replaces({StartKind::Rigid, 0.31, never}, {StartKind::Intrinsic, 0.3, never}));
}

// An intrinsic start's result replaces a rigid start's outright below (1 − kIntrinsicMargin)
// times its disagreement; nearer a tie only if its turning functions agree about as well.
TEST(Selection, IntrinsicResultNeedsAMarginOrTheTurningFunctions) {
    const double kept = 0.4;
    const double clearly = (1 - kIntrinsicMargin) * kept - 1e-9;
    EXPECT_TRUE(replaces(intrinsic(clearly, -1.0), rigid(kept, 1.0)));
    const double near_tie = 0.38;
    EXPECT_TRUE(replaces(intrinsic(near_tie, 0.60), rigid(kept, 0.61)));
    EXPECT_TRUE(replaces(intrinsic(near_tie, 0.50 - kIntrinsicTurning), rigid(kept, 0.50)));
    EXPECT_FALSE(replaces(intrinsic(near_tie, 0.37), rigid(kept, 0.50)));
    EXPECT_FALSE(replaces(intrinsic(0.41, 0.9), rigid(kept, 0.1)));  // disagrees more
}

TEST(Selection, DoubtfulResultsAskForTheFallbackAndTheOtherStarts) {
    EXPECT_FALSE(is_doubtful(kDoubtfulDisagreement));
    EXPECT_TRUE(is_doubtful(std::nextafter(kDoubtfulDisagreement, 1.0)));
    EXPECT_TRUE(needs_signature_fallback(0.5));
    EXPECT_FALSE(needs_signature_fallback(0.2));
    // The second opinion: at 0 it is asked of every match up front, not here; +inf never.
    EXPECT_FALSE(needs_second_opinion(10, 0));
    EXPECT_FALSE(needs_second_opinion(10, std::numeric_limits<double>::infinity()));
    EXPECT_TRUE(needs_second_opinion(0.4, 0.35));
    EXPECT_FALSE(needs_second_opinion(0.3, 0.35));
    // The next landmark sets: above their own bound, or doubtful even where the bound is higher.
    EXPECT_TRUE(needs_alternative_starts(0.2, 0.15));
    EXPECT_FALSE(needs_alternative_starts(0.1, 0.15));
    EXPECT_FALSE(needs_alternative_starts(0.15, 0.15));
    EXPECT_TRUE(needs_alternative_starts(0.5, std::numeric_limits<double>::infinity()));
    EXPECT_FALSE(needs_alternative_starts(0.3, std::numeric_limits<double>::infinity()));
}

// The match from exchanged limbs is kept only if every condition holds: agreement as a right
// map's, clearly better than before, the disagreement about as low, the extremities in place.
TEST(Selection, LimbExchangeKeptOnlyWhenEveryConditionHolds) {
    const LimbExchange right{.agreement_before = 0.2,
                             .agreement_after = 0.55,
                             .disagreement_before = 0.20,
                             .disagreement_after = 0.21,
                             .drift = 0.1};
    EXPECT_TRUE(keeps_limb_exchange(right));
    LimbExchange no_drift = right;
    no_drift.drift.reset();  // the refined level's check does not ask it
    EXPECT_TRUE(keeps_limb_exchange(no_drift));
    LimbExchange drifted = right;
    drifted.drift = kLimbSwapDrift * 1.01;
    EXPECT_FALSE(keeps_limb_exchange(drifted));
    LimbExchange weak = right;
    weak.agreement_after = kLimbSwapAgreement - 0.01;
    EXPECT_FALSE(keeps_limb_exchange(weak));
    LimbExchange small_gain = right;
    small_gain.agreement_before = right.agreement_after - kLimbSwapMargin;
    EXPECT_FALSE(keeps_limb_exchange(small_gain));
    LimbExchange disagrees = right;
    disagrees.disagreement_after = (1 + kLimbSwapDisagreement) * 0.20 * 1.01;
    EXPECT_FALSE(keeps_limb_exchange(disagrees));
}

TEST(Selection, TurnedBackLevelKeptWhileTheDistanceStaysAboutAsLow) {
    EXPECT_TRUE(keeps_turned_back(1.0, 1.0));
    EXPECT_TRUE(keeps_turned_back(kTurnBackAllowance, 1.0));
    EXPECT_FALSE(keeps_turned_back(kTurnBackAllowance * 1.01, 1.0));
}

// Of flows side by side the lowest rating is kept and every flow's steps are counted; once
// cancelled, the first.
TEST(Selection, KeepLowestCountsEveryFlowAndKeepsTheFirstWhenCancelled) {
    std::vector<FlowResult> flows(3);
    const std::vector<double> ratings{0.3, 0.1, 0.2};
    for (std::size_t k = 0; k < flows.size(); ++k) {
        flows[k].steps = static_cast<int>(10 * (k + 1));
        flows[k].energy = {ratings[k]};
    }
    const auto rate = [](const FlowResult& flow) { return flow.energy.back(); };
    std::atomic<bool> cancelled = false;
    const KeptFlow kept = keep_lowest(flows, cancelled, rate);
    EXPECT_EQ(kept.index, 1U);
    EXPECT_EQ(kept.rating, 0.1);
    EXPECT_EQ(kept.steps, 60);
    cancelled = true;
    EXPECT_EQ(keep_lowest(flows, cancelled, rate).index, 0U);
}

ReadingScore commuting(double commutativity, std::optional<double> orientation = 0.2) {
    ReadingScore score;
    score.commutativity = commutativity;
    score.orientation_ratio = orientation;
    return score;
}

// The reading whose map commutes better is kept; a tie keeps the first. The orientation is
// reported, not judged (docs/benchmarks.md, "The readings off as a whole lie turned about").
TEST(Selection, SignaturesReadingKeptWhereItCommutesBetter) {
    EXPECT_TRUE(keeps_signatures_reading(commuting(0.02), commuting(0.03)));
    EXPECT_FALSE(keeps_signatures_reading(commuting(0.03), commuting(0.02)));
    EXPECT_FALSE(keeps_signatures_reading(commuting(0.02), commuting(0.02)));
    EXPECT_TRUE(keeps_signatures_reading(commuting(0.02, 3.0), commuting(0.03)));
    EXPECT_FALSE(keeps_signatures_reading(commuting(0.03, std::nullopt), commuting(0.02, 3.0)));
}

}  // namespace
}  // namespace genflow::detail
