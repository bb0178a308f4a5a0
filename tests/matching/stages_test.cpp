// SPDX-License-Identifier: MIT
// The matcher's stages on a generated pair: prepare() (rigid starts, pyramid), the flow of one
// level (LevelFlows, with its memo), the guided rounds, the coarsest level and the finer levels;
// and the clock that times them.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <chrono>
#include <limits>
#include <thread>
#include <utility>

#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"
#include "matching/coarsest_level.h"
#include "matching/finer_levels.h"
#include "matching/flow_memo.h"
#include "matching/guided_rounds.h"
#include "matching/level_flow.h"
#include "matching/prepare.h"
#include "matching/selection.h"
#include "matching/spectral_descriptors.h"
#include "matching/stopwatch.h"

namespace genflow::detail {
namespace {

// Each end() times the stage since the previous one; a stage ended twice adds up and keeps its
// first place; a prefix names the stages ended after it apart; seconds() reads one by name.
TEST(StageClock, AddsUpAStageEndedTwiceAndKeepsTheOrder) {
    using namespace std::chrono_literals;
    StageClock clock;
    std::this_thread::sleep_for(10ms);
    clock.end("first");
    clock.end("second");
    std::this_thread::sleep_for(10ms);
    clock.end("first");
    clock.name_from_now("again: ");
    clock.end("first");
    clock.name_from_now("");
    clock.end("second");
    ASSERT_EQ(clock.times().size(), 3U);
    EXPECT_EQ(clock.times()[0].stage, "first");
    EXPECT_EQ(clock.times()[1].stage, "second");
    EXPECT_EQ(clock.times()[2].stage, "again: first");
    EXPECT_GE(clock.times()[0].seconds, 0.02);  // both sleeps; a sleep lasts at least its time
    EXPECT_EQ(clock.seconds("first"), clock.times()[0].seconds);
    EXPECT_EQ(clock.seconds("again: first"), clock.times()[2].seconds);
    EXPECT_EQ(clock.seconds("never"), 0);
    for (const MatchStageTime& time : clock.times()) {
        EXPECT_GE(time.seconds, 0);
        EXPECT_GE(time.processor_seconds, 0);
    }
}

// The generated limb and another sampling of it, moved: a pair alike up to a similarity.
struct MovedLimb {
    TriangleMesh template_mesh = make_limb(4);
    TriangleMesh target = make_limb(4, 5);
    MovedLimb() { target.V.rowwise() += Eigen::RowVector3d(0.3, -0.2, 0.1); }
};

// Finest level first, the inputs themselves; each coarser template about a quarter of the one
// before and its vertices a subset of the template's; the coarsest near coarse_vertices.
TEST(Prepare, BuildsANestedPyramidAndTheRigidStarts) {
    const MovedLimb pair;
    MatchOptions options;
    options.coarse_vertices = 300;
    options.starts.candidates = 3;
    StageClock clock;
    const Prepared prepared = prepare(pair.template_mesh, pair.target, options, clock);
    ASSERT_GE(prepared.pyramid.size(), 2U);
    EXPECT_EQ(prepared.pyramid.front().template_mesh.V, pair.template_mesh.V);
    EXPECT_EQ(prepared.pyramid.front().target.V, pair.target.V);
    for (std::size_t l = 1; l < prepared.pyramid.size(); ++l) {
        const Level& level = prepared.pyramid[l];
        const Eigen::Index finer = prepared.pyramid[l - 1].template_mesh.V.rows();
        EXPECT_NEAR(static_cast<double>(level.template_mesh.V.rows()), finer / 4.0, 0.1 * finer);
        ASSERT_EQ(level.original_vertex.size(),
                  static_cast<std::size_t>(level.template_mesh.V.rows()));
        for (std::size_t k = 0; k < level.original_vertex.size(); ++k) {
            EXPECT_EQ(level.template_mesh.V.row(static_cast<Eigen::Index>(k)),
                      pair.template_mesh.V.row(level.original_vertex[k]));
        }
    }
    EXPECT_LE(prepared.pyramid.back().template_mesh.V.rows(), 2 * options.coarse_vertices);
    EXPECT_EQ(prepared.starts.size(), 3U);
    EXPECT_FALSE(prepared.volume_scale.has_value());  // a smooth target: the areas hold

    options.starts.enabled = false;  // the inputs as they are placed
    const Prepared unaligned = prepare(pair.template_mesh, pair.target, options, clock);
    ASSERT_EQ(unaligned.starts.size(), 1U);
    EXPECT_EQ(unaligned.starts.front().matrix(), Eigen::Matrix4d::Identity());
}

// A level's flow lowers d_H at every step from the template's place; a progress call that says stop
// cancels it and every other flow that shares the flag.
TEST(LevelFlows, LowerTheDistanceAndStopWhenCancelled) {
    const MovedLimb pair;
    MatchOptions options;
    options.coarse_vertices = 300;
    StageClock clock;
    const Prepared prepared = prepare(pair.template_mesh, pair.target, options, clock);
    std::atomic<bool> cancelled = false;
    const LevelFlows flows(prepared.pyramid, options, bounding_box_diagonal(pair.target),
                           cancelled);
    const int coarsest = static_cast<int>(prepared.pyramid.size()) - 1;
    const Level& level = prepared.pyramid.back();
    const FlowResult flow = flows.flow(coarsest, level.template_mesh, 40, {}, MatchPrior::H1);
    ASSERT_TRUE(flow.ok()) << flow.message;
    for (std::size_t k = 1; k < flow.energy.size(); ++k) {
        EXPECT_LT(flow.energy[k], flow.energy[k - 1]) << k;
    }
    EXPECT_LT(flow.energy.back(), 0.8 * flow.energy.front());
    EXPECT_NEAR(flow.energy.front(),
                flows.distance_to_target(level, 1, {}).value(level.template_mesh),
                1e-12 * flow.energy.front());
    EXPECT_FALSE(cancelled);

    options.progress = [](const MatchProgress& progress) { return progress.step < 3; };
    const LevelFlows stopping(prepared.pyramid, options, bounding_box_diagonal(pair.target),
                              cancelled);
    const FlowResult stopped = stopping.flow(coarsest, level.template_mesh, 40, {}, MatchPrior::H1);
    EXPECT_EQ(stopped.status, FlowStatus::Cancelled);
    EXPECT_EQ(stopped.steps, 3);
    EXPECT_TRUE(cancelled);
}

// A repeated coarsest flow comes from the memo, equal to the bit to the flow run anew; a finer
// level's flows are not kept (the large ones, which the readings do not repeat).
TEST(LevelFlows, AnswerTheCoarsestLevelsRepeatedFlowsFromTheMemo) {
    const MovedLimb pair;
    MatchOptions options;
    options.coarse_vertices = 300;
    StageClock clock;
    const Prepared prepared = prepare(pair.template_mesh, pair.target, options, clock);
    ASSERT_GE(prepared.pyramid.size(), 2U);
    const double diagonal = bounding_box_diagonal(pair.target);
    std::atomic<bool> cancelled = false;
    FlowMemo memo;
    const LevelFlows memoized(prepared.pyramid, options, diagonal, cancelled, &memo);
    const LevelFlows plain(prepared.pyramid, options, diagonal, cancelled);
    const int coarsest = memoized.coarsest();
    const TriangleMesh& start = prepared.pyramid.back().template_mesh;

    const FlowResult first = memoized.flow(coarsest, start, 25, {}, MatchPrior::H1, {}, 0.1);
    const FlowResult again = memoized.flow(coarsest, start, 25, {}, MatchPrior::H1, {}, 0.1);
    const FlowResult anew = plain.flow(coarsest, start, 25, {}, MatchPrior::H1, {}, 0.1);
    EXPECT_EQ(memo.reused(), 1);
    EXPECT_GT(first.steps, 0);
    for (const FlowResult* result : {&again, &anew}) {
        EXPECT_EQ(result->mesh.V, first.mesh.V);
        EXPECT_EQ(result->energy, first.energy);
        EXPECT_EQ(result->steps, first.steps);
    }
    const FlowResult longer = memoized.flow(coarsest, start, 26, {}, MatchPrior::H1, {}, 0.1);
    EXPECT_EQ(memo.reused(), 1);
    EXPECT_GE(longer.steps, first.steps);

    const TriangleMesh& finest = prepared.pyramid.front().template_mesh;
    (void)memoized.flow(0, finest, 3, {}, MatchPrior::H1);
    (void)memoized.flow(0, finest, 3, {}, MatchPrior::H1);
    EXPECT_EQ(memo.reused(), 1);
}

// A pair prepared with short flows, for the stages after prepare().
struct PreparedLimb {
    MovedLimb pair;
    MatchOptions options;
    Prepared prepared;
    mutable std::atomic<bool> cancelled = false;
    mutable StageClock clock;
    double diagonal = bounding_box_diagonal(pair.target);

    explicit PreparedLimb(MatchOptions base = {}) : options(std::move(base)) {
        options.coarse_vertices = 300;
        options.max_iterations = 60;
        options.fine_iterations = 5;
        options.refinement_iterations = 5;
        options.starts.selection_iterations = 20;
        options.starts.candidates = 2;
        prepared = prepare(pair.template_mesh, pair.target, options, clock);
    }
    [[nodiscard]] const Level& coarsest() const { return prepared.pyramid.back(); }
    [[nodiscard]] SpectralDescriptors analysis() const {
        return {coarsest().template_mesh, coarsest().target};
    }
};

// Guided rounds run where they were measured to pay (h1, articulated, isometric), and the
// quasi-isometric prior decides in the H1 metric.
TEST(GuidedRounds, RunForTheBendingPriorsAndDecideInH1) {
    MatchOptions options;
    for (const MatchPrior prior : kMatchPriors) {
        options.prior = prior;
        const bool bends = prior == MatchPrior::H1 || prior == MatchPrior::Articulated ||
                           prior == MatchPrior::Isometric;
        EXPECT_EQ(runs_guided_rounds(options), bends) << to_string(prior);
        EXPECT_EQ(guided_prior(prior), prior == MatchPrior::Isometric ? MatchPrior::H1 : prior);
    }
    options.prior = MatchPrior::H1;
    options.guided.signature_guidance = 0;
    EXPECT_FALSE(runs_guided_rounds(options));
}

// One start's rounds: the plain d_H falls from the start's placement, every round's steps are
// counted, the kept stiffness is one of the candidates, and the reported disagreement is the
// result's.
TEST(GuidedRounds, LowerThePlainDistanceAndReportTheKeptCandidate) {
    const PreparedLimb limb;
    const SpectralDescriptors analysis = limb.analysis();
    const LevelFlows flows(limb.prepared.pyramid, limb.options, limb.diagonal, limb.cancelled);
    const GuidedRounds rounds(limb.prepared.pyramid, flows, analysis, limb.options, limb.diagonal,
                              limb.cancelled);
    const Similarity start = limb.prepared.starts.front();
    const GuidedMatch outcome = rounds.match({.placement = start}, false);
    ASSERT_TRUE(outcome.flow.ok()) << outcome.flow.message;
    TriangleMesh placed = limb.coarsest().template_mesh;
    placed.V = start.apply(placed.V);
    const PseudoHausdorffEnergy plain = flows.distance_to_target(limb.coarsest(), 1, {});
    EXPECT_DOUBLE_EQ(outcome.flow.energy.front(), plain.value(placed));
    EXPECT_DOUBLE_EQ(outcome.flow.energy.back(), plain.value(outcome.flow.mesh));
    EXPECT_LT(outcome.flow.energy.back(), outcome.flow.energy.front());
    // Signature-guided then plain, and per stiffness guided then plain (then settled): at least
    // one step each.
    EXPECT_GE(outcome.flow.steps, 2 + 2 * limb.options.guided.stiffness_candidates);
    const double w = limb.options.guided.stretch_weight;
    EXPECT_TRUE(outcome.stretch_weight == w || outcome.stretch_weight == 4 * w ||
                outcome.stretch_weight == 16 * w)
        << outcome.stretch_weight;
    EXPECT_EQ(outcome.eigenfunction_guidance, limb.options.guided.eigenfunction_guidance);
    EXPECT_DOUBLE_EQ(outcome.disagreement, disagreement(analysis, outcome.flow.mesh.V));
    EXPECT_FALSE(outcome.signatures_alone);

    // A match again from a result with the last round guided by the signatures alone.
    const GuidedMatch again = rounds.match(
        {.placement = start, .from = &outcome.flow.mesh, .signatures_alone = true}, false);
    EXPECT_TRUE(again.signatures_alone);
    EXPECT_EQ(again.eigenfunction_guidance, 0);
    EXPECT_DOUBLE_EQ(again.flow.energy.front(), plain.value(outcome.flow.mesh));
}

// The coarsest level keeps a start that brings the template onto the target; the second
// opinion is reported exactly when it was asked, and an unguided prior flows from a rigid start.
TEST(CoarsestLevel, KeepsAStartOnTheTargetAndReportsTheSecondOpinion) {
    for (const double second_opinion_above : {0.0, std::numeric_limits<double>::infinity()}) {
        MatchOptions options;
        options.second_opinion.above = second_opinion_above;
        options.second_opinion.alternative_starts = 0;
        PreparedLimb limb(options);
        const SpectralDescriptors analysis = limb.analysis();
        const LevelFlows flows(limb.prepared.pyramid, limb.options, limb.diagonal, limb.cancelled);
        const CoarsestMatch match =
            match_coarsest_level(limb.prepared, flows, &analysis, limb.options, limb.diagonal,
                                 limb.cancelled, limb.clock);
        ASSERT_TRUE(match.flow.ok()) << match.flow.message;
        EXPECT_LT(match.flow.energy.back(), match.flow.energy.front());
        EXPECT_LT(disagreement(analysis, match.flow.mesh.V), kDoubtfulDisagreement);
        EXPECT_EQ(match.second_opinion_disagreement.has_value(), second_opinion_above == 0);
        EXPECT_EQ(match.alternative_starts, 0);
    }
    MatchOptions options;
    options.prior = MatchPrior::L2;
    PreparedLimb limb(options);
    const SpectralDescriptors analysis = limb.analysis();
    const LevelFlows flows(limb.prepared.pyramid, limb.options, limb.diagonal, limb.cancelled);
    const CoarsestMatch match = match_coarsest_level(limb.prepared, flows, &analysis, limb.options,
                                                     limb.diagonal, limb.cancelled, limb.clock);
    ASSERT_TRUE(match.flow.ok()) << match.flow.message;
    bool rigid_start = false;
    for (const Similarity& start : limb.prepared.starts) {
        rigid_start = rigid_start || start.matrix() == match.start.matrix();
    }
    EXPECT_TRUE(rigid_start);
    EXPECT_FALSE(match.second_opinion_disagreement.has_value());
    EXPECT_EQ(match.stretch_weight, 0);
}

// The finer levels report one level each, end at the template's resolution and closer to the
// target than the carried coarsest result; cancelled, they still return every vertex.
TEST(FinerLevels, CarryTheCoarsestResultToTheTemplatesResolution) {
    PreparedLimb limb;
    const SpectralDescriptors analysis = limb.analysis();
    const LevelFlows flows(limb.prepared.pyramid, limb.options, limb.diagonal, limb.cancelled);
    const CoarsestMatch coarsest = match_coarsest_level(
        limb.prepared, flows, &analysis, limb.options, limb.diagonal, limb.cancelled, limb.clock);
    FinerLevels finer(limb.prepared.pyramid, flows, &analysis, limb.options, limb.diagonal,
                      limb.cancelled, coarsest.start, coarsest.stretch_weight);
    const FinerMatch finest = finer.match(coarsest.flow.mesh.V, limb.clock);
    const auto count = limb.prepared.pyramid.size();
    ASSERT_EQ(finest.levels.size(), count - 1);
    EXPECT_EQ(finest.levels.back().template_vertices, limb.pair.template_mesh.V.rows());
    ASSERT_EQ(finest.deformed.rows(), limb.pair.template_mesh.V.rows());
    for (const MatchLevel& level : finest.levels) {
        EXPECT_LE(level.energy_end, level.energy_start);
    }

    MatchOptions stopping = limb.options;
    stopping.progress = [](const MatchProgress& progress) { return progress.step < 2; };
    std::atomic<bool> cancelled = false;
    const LevelFlows stopped_flows(limb.prepared.pyramid, stopping, limb.diagonal, cancelled);
    FinerLevels stopped(limb.prepared.pyramid, stopped_flows, &analysis, stopping, limb.diagonal,
                        cancelled, coarsest.start, coarsest.stretch_weight);
    const FinerMatch partial = stopped.match(coarsest.flow.mesh.V, limb.clock);
    EXPECT_TRUE(cancelled);
    EXPECT_LT(partial.levels.size(), count - 1);
    EXPECT_EQ(partial.deformed.rows(), limb.pair.template_mesh.V.rows());
}

// A finer-level stage that kept nothing left the match as if it had not run (its rules keep a
// candidate or leave everything as it was), which is what lets bench/ablation.sh take the
// default's result for every pair where the stage kept nothing.
TEST(FinerLevels, AStageThatKeptNothingLeavesTheMatchAsItWas) {
    const PreparedLimb limb;
    const SpectralDescriptors analysis = limb.analysis();
    const LevelFlows flows(limb.prepared.pyramid, limb.options, limb.diagonal, limb.cancelled);
    const CoarsestMatch coarsest = match_coarsest_level(
        limb.prepared, flows, &analysis, limb.options, limb.diagonal, limb.cancelled, limb.clock);
    const auto finer_match = [&](const MatchOptions& options) {
        const LevelFlows level_flows(limb.prepared.pyramid, options, limb.diagonal, limb.cancelled);
        FinerLevels finer(limb.prepared.pyramid, level_flows, &analysis, options, limb.diagonal,
                          limb.cancelled, coarsest.start, coarsest.stretch_weight);
        return finer.match(coarsest.flow.mesh.V, limb.clock);
    };
    const FinerMatch all = finer_match(limb.options);
    // Each stage: whether it kept anything in the match with all of them, and its switch.
    struct Stage {
        const char* name;
        bool kept;
        bool* enabled;
    };
    MatchOptions options = limb.options;
    const std::array<Stage, 4> stages{{
        {"refinement", all.refinement_guidance != 0, &options.refinement.enabled},
        {"turn-back", all.turned_parts != 0, &options.turn_back.enabled},
        {"map fits", all.map_fits != 0, &options.map_fit.enabled},
        {"limb swaps", all.swapped_limbs != 0, &options.limb_swaps.enabled},
    }};
    int checked = 0;
    for (const Stage& stage : stages) {
        if (stage.kept) {
            continue;
        }
        *stage.enabled = false;
        EXPECT_EQ(finer_match(options).deformed, all.deformed) << stage.name;
        *stage.enabled = true;
        ++checked;
    }
    EXPECT_GE(checked, 2);
}

}  // namespace
}  // namespace genflow::detail
