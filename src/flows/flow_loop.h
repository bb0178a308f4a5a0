// SPDX-License-Identifier: MIT
// The one step loop of genflow's flows: the energy log, progress and cancelling, the stopping
// rules, and breakdowns turned into a status instead of garbage. How far each step goes is the
// integrator's step-control policy: a fixed time step (explicit_euler(), implicit_euler()) or a
// line search with Armijo backtracking (gradient_descent()).
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "genflow/energies/energy.h"
#include "genflow/flows/flow.h"
#include "genflow/metrics/metric.h"

namespace genflow::detail {

/// When the loop stops, besides a policy that has no step to take.
struct StoppingRules {
    int max_steps = 100;  ///< steps taken at most (MaxSteps)
    double max_seconds = std::numeric_limits<double>::infinity();  ///< after a step (TimeLimit)
    /// Converged once E ≤ this, checked before each step.
    double target_energy = -std::numeric_limits<double>::infinity();
    /// Converged once |E_k − E_{k−1}| ≤ energy_tolerance·|E_0| (0: never).
    double energy_tolerance = 0;
    /// Converged once E fell by no more than stagnation_tolerance·|E| over the last
    /// stagnation_window steps (window 0: never).
    double stagnation_tolerance = 0;
    int stagnation_window = 0;
};

/// What a step-control policy proposes: the next positions and their energy, or no step and
/// the status that ends the flow (Converged at a stationary point or where no step descends,
/// NonFinite for a non-finite gradient) with why, if it says: the loop names the integrator
/// and the step ("<caller>: <message> at step N").
struct ProposedStep {
    std::optional<TriangleMesh> next = std::nullopt;
    double value = 0;
    FlowStatus stop = FlowStatus::Converged;
    std::string message = {};
};

/// A step-control policy: from the current mesh (the metric already updated to it) and its
/// energy, the next step. It may throw SolverError (the flow stops as SolverFailed).
using StepPolicy = std::function<ProposedStep(const TriangleMesh& current, double value)>;

/// What a step-control policy can do for its next step from the current mesh alone, before
/// the step, while the metric updates to that mesh (Metric::update_alongside()).
using StepPreparation = std::function<void(const TriangleMesh& current)>;

/// Runs `policy` from `mesh` until a stopping rule fires, calling `progress` after every step.
/// The first `metric.update()` happens before the loop, so a mesh the metric refuses is an
/// exception, not a status; an energy that is not finite at the input or after a step ends the
/// flow as NonFinite. `prepare`, if any, runs alongside each update of the metric, on the mesh
/// the policy then steps from. `caller` names the integrator in messages.
FlowResult run_flow(const TriangleMesh& mesh, const Energy& energy, Metric& metric,
                    const StoppingRules& rules,
                    const std::function<bool(const FlowProgress&)>& progress,
                    const StepPolicy& policy, const char* caller,
                    const StepPreparation& prepare = {});

/// The fixed-step policy of the Euler integrators: the displacement `displacement` returns for
/// the current mesh is added whole.
[[nodiscard]] StepPolicy fixed_step(
    const Energy& energy, const std::function<VertexField(const TriangleMesh&)>& displacement);

/// The stopping rules of FlowOptions; throws InvalidInput naming `caller` on a bad option.
[[nodiscard]] StoppingRules stopping_rules(const FlowOptions& options, const char* caller);

}  // namespace genflow::detail
