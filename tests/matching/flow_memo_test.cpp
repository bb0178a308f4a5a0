// SPDX-License-Identifier: MIT
// FlowMemo: a flow's result found again for the same request and for no other (LevelFlows
// answering from it: stages_test.cpp).
#include "matching/flow_memo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>

#include "genflow/mesh/primitives.h"

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

}  // namespace
}  // namespace genflow::detail
