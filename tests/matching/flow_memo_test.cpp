// SPDX-License-Identifier: MIT
// FlowMemo: a flow's result found again for the same request and for no other; LevelFlows
// answering the coarsest level's repeated flows from it, equal to the bit to the flow run anew.
#include "matching/flow_memo.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <functional>
#include <optional>

#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"
#include "matching/level_flow.h"
#include "matching/prepare.h"

namespace genflow::detail {
namespace {

// rows×cols values that differ from entry to entry, the same at every call.
Eigen::MatrixXd filled(Eigen::Index rows, Eigen::Index cols, double phase) {
    Eigen::MatrixXd m(rows, cols);
    for (Eigen::Index k = 0; k < m.size(); ++k) {
        m.data()[k] = std::sin(phase + 0.7 * static_cast<double>(k));
    }
    return m;
}

// A request's inputs, owned, so that a test can change one and keep the others.
struct Inputs {
    Eigen::MatrixX3d start = filled(12, 3, 0.0);
    Similarity placement;
    PointDescriptors descriptors{filled(12, 4, 1.0), filled(9, 4, 2.0)};
    int level = 1;
    int iterations = 30;
    MatchPrior prior = MatchPrior::H1;
    double stretch_weight = 0.1;

    [[nodiscard]] FlowRequest request() const {
        return {level, &start, iterations, &placement, prior, &descriptors, stretch_weight};
    }
};

FlowResult some_result() {
    FlowResult result;
    result.mesh = make_icosphere(1);
    result.steps = 7;
    result.energy = {3.0, 2.0, 1.5};
    result.status = FlowStatus::Converged;
    return result;
}

TEST(FlowMemo, FindsAKeptFlowForTheSameRequestOnly) {
    FlowMemo memo;
    const Inputs kept;
    EXPECT_FALSE(memo.find(kept.request()).has_value());
    memo.keep(kept.request(), some_result());

    const Inputs same;  // other storage, the same values
    const std::optional<FlowResult> found = memo.find(same.request());
    ASSERT_TRUE(found.has_value());
    EXPECT_EQ(found->mesh.V, some_result().mesh.V);
    EXPECT_EQ(found->energy, some_result().energy);
    EXPECT_EQ(found->steps, 7);
    EXPECT_EQ(memo.reused(), 1);

    // Any one input changed, by as little as a last bit, is another flow.
    const std::vector<std::function<void(Inputs&)>> changes{
        [](Inputs& in) { in.start(5, 1) = std::nextafter(in.start(5, 1), 2.0); },
        [](Inputs& in) { in.placement.scale = 1.0 + 1e-15; },
        [](Inputs& in) { in.placement.translation.z() = 1e-300; },
        [](Inputs& in) { in.placement.rotation(0, 1) = 1e-300; },
        [](Inputs& in) { in.descriptors.moving(3, 2) *= 2; },
        [](Inputs& in) { in.descriptors.fixed(8, 0) *= 2; },
        [](Inputs& in) { in.descriptors = {}; },
        [](Inputs& in) { in.level = 0; },
        [](Inputs& in) { in.iterations = 31; },
        [](Inputs& in) { in.prior = MatchPrior::Isometric; },
        [](Inputs& in) { in.stretch_weight = 0.4; },
    };
    for (std::size_t k = 0; k < changes.size(); ++k) {
        Inputs other;
        changes[k](other);
        EXPECT_FALSE(memo.find(other.request()).has_value()) << "change " << k;
    }
    EXPECT_EQ(memo.reused(), 1);
}

// The first result kept for a request stays: a flow is a function of its request, and a second
// result for it can only be the same one.
TEST(FlowMemo, KeepsTheFirstResultOfARequest) {
    FlowMemo memo;
    const Inputs inputs;
    memo.keep(inputs.request(), some_result());
    FlowResult other = some_result();
    other.steps = 99;
    memo.keep(inputs.request(), other);
    EXPECT_EQ(memo.find(inputs.request())->steps, 7);
}

// The generated limb and another sampling of it, moved, prepared with a small coarsest level.
struct PreparedLimb {
    TriangleMesh template_mesh = make_limb(4);
    TriangleMesh target = make_limb(4, 5);
    MatchOptions options;
    Prepared prepared;

    PreparedLimb() {
        target.V.rowwise() += Eigen::RowVector3d(0.3, -0.2, 0.1);
        options.coarse_vertices = 300;
        prepared = prepare(template_mesh, target, options);
    }
};

// A repeated coarsest flow comes from the memo, equal to the bit to the flow run anew; a finer
// level's flows are not kept (the large ones, which the readings do not repeat).
TEST(LevelFlows, AnswerTheCoarsestLevelsRepeatedFlowsFromTheMemo) {
    const PreparedLimb limb;
    ASSERT_GE(limb.prepared.pyramid.size(), 2U);
    const double diagonal = bounding_box_diagonal(limb.target);
    std::atomic<bool> cancelled = false;
    FlowMemo memo;
    const LevelFlows memoized(limb.prepared.pyramid, limb.options, diagonal, cancelled, &memo);
    const LevelFlows plain(limb.prepared.pyramid, limb.options, diagonal, cancelled);
    const int coarsest = memoized.coarsest();
    const TriangleMesh& start = limb.prepared.pyramid.back().template_mesh;

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

    const TriangleMesh& finest = limb.prepared.pyramid.front().template_mesh;
    (void)memoized.flow(0, finest, 3, {}, MatchPrior::H1);
    (void)memoized.flow(0, finest, 3, {}, MatchPrior::H1);
    EXPECT_EQ(memo.reused(), 1);
}

}  // namespace
}  // namespace genflow::detail
