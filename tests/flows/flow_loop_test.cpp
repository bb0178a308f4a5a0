// SPDX-License-Identifier: MIT
// The one step loop (flows/flow_loop.h) under scripted step-control policies: each stopping
// rule ends the flow with its status, and a policy's stop or breakdown becomes a status.
#include "flows/flow_loop.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "genflow/energies/surface_area_energy.h"
#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/metrics/l2_metric.h"
#include "genflow/metrics/sobolev_metric.h"

namespace genflow::detail {
namespace {

// A policy that takes the mesh as it is and reports the energies of `values` in turn, then
// stops (Converged).
StepPolicy scripted(std::vector<double> values) {
    return [values, k = std::size_t{0}](const TriangleMesh& current, double) mutable {
        ProposedStep step;
        if (k < values.size()) {
            step.next = current;
            step.value = values[k++];
        }
        return step;
    };
}

struct Loop {
    TriangleMesh mesh = make_icosphere(1);
    SurfaceAreaEnergy energy;
    L2Metric metric;
    FlowResult run(const StoppingRules& rules, const StepPolicy& policy,
                   const std::function<bool(const FlowProgress&)>& progress = {}) {
        return run_flow(mesh, energy, metric, rules, progress, policy, "test");
    }
};

TEST(FlowLoop, EachStoppingRuleEndsTheFlowWithItsStatus) {
    Loop loop;
    const double e0 = SurfaceAreaEnergy().value(loop.mesh);
    FlowResult result = loop.run({.max_steps = 3}, scripted({5, 4, 3, 2}));
    EXPECT_EQ(result.status, FlowStatus::MaxSteps);
    EXPECT_EQ(result.energy, (std::vector<double>{e0, 5, 4, 3}));

    result = loop.run({.max_steps = 10}, scripted({5, 4}));
    EXPECT_EQ(result.status, FlowStatus::Converged);  // the policy had no step left
    EXPECT_EQ(result.steps, 2);

    result = loop.run({.max_steps = 10, .target_energy = 4}, scripted({5, 4, 3}));
    EXPECT_EQ(result.status, FlowStatus::Converged);
    EXPECT_EQ(result.energy.back(), 4);

    // |E_k − E_{k−1}| ≤ tolerance·|E_0|: 4.0 → 3.999 changes by less than 1e-3·e0.
    result = loop.run({.max_steps = 10, .energy_tolerance = 1e-3 / e0}, scripted({5, 4, 3.9995}));
    EXPECT_EQ(result.status, FlowStatus::Converged);
    EXPECT_EQ(result.steps, 3);

    // Over a window of 2 steps E fell by no more than 1 % of E.
    result = loop.run({.max_steps = 10, .stagnation_tolerance = 0.01, .stagnation_window = 2},
                      scripted({5, 4, 3.99, 3.985, 1}));
    EXPECT_EQ(result.status, FlowStatus::Converged);
    EXPECT_EQ(result.steps, 4);

    result = loop.run({.max_steps = 10}, scripted({5, 4, 3}),
                      [](const FlowProgress& p) { return p.step < 2; });
    EXPECT_EQ(result.status, FlowStatus::Cancelled);
    EXPECT_EQ(result.steps, 2);
}

// A flow of no step needs no metric: its factorization would cost several steps.
TEST(FlowLoop, AFlowOfNoStepLeavesTheMetricAlone) {
    Loop loop;
    H1Metric metric({.lambda = 0.1});
    const FlowResult none =
        run_flow(loop.mesh, loop.energy, metric, {.max_steps = 0}, {}, scripted({5}), "test");
    EXPECT_EQ(none.steps, 0);
    EXPECT_EQ(none.energy.size(), 1U);  // the input's energy, all the same
    EXPECT_EQ(metric.symbolic_analyses(), 0);
    const FlowResult one =
        run_flow(loop.mesh, loop.energy, metric, {.max_steps = 1}, {}, scripted({5}), "test");
    EXPECT_EQ(one.steps, 1);
    EXPECT_EQ(metric.symbolic_analyses(), 1);
}

TEST(FlowLoop, PolicyStopsAndBreakdownsBecomeStatuses) {
    Loop loop;
    FlowResult result = loop.run({.max_steps = 5}, [](const TriangleMesh&, double) {
        return ProposedStep{.stop = FlowStatus::NonFinite, .message = "why"};
    });
    EXPECT_EQ(result.status, FlowStatus::NonFinite);
    EXPECT_EQ(result.message, "test: why at step 1");
    EXPECT_EQ(result.steps, 0);

    result = loop.run({.max_steps = 5}, scripted({5, NAN}));
    EXPECT_EQ(result.status, FlowStatus::NonFinite);
    EXPECT_EQ(result.steps, 1);
    EXPECT_FALSE(result.ok());
    EXPECT_NE(result.message.find("test: step 2"), std::string::npos) << result.message;

    result = loop.run({.max_steps = 5}, [](const TriangleMesh&, double) -> ProposedStep {
        throw SolverError("no factorization");
    });
    EXPECT_EQ(result.status, FlowStatus::SolverFailed);
    EXPECT_EQ(result.message, "no factorization");
}

}  // namespace
}  // namespace genflow::detail
