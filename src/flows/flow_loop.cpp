// SPDX-License-Identifier: MIT
#include "flows/flow_loop.h"

#include <chrono>
#include <cmath>
#include <string>

#include "genflow/exceptions.h"
#include "operators/triangle.h"

namespace genflow {

const char* to_string(FlowStatus status) {
    switch (status) {
        case FlowStatus::Converged:
            return "converged";
        case FlowStatus::MaxSteps:
            return "max-steps";
        case FlowStatus::TimeLimit:
            return "time-limit";
        case FlowStatus::Cancelled:
            return "cancelled";
        case FlowStatus::NonFinite:
            return "non-finite";
        case FlowStatus::SolverFailed:
            return "solver-failed";
    }
    return "unknown";
}

namespace detail {

namespace {

// Whether a stopping rule that looks at the energy log fires after the latest step.
bool settled(const StoppingRules& rules, const std::vector<double>& energy) {
    const double value = energy.back();
    const double change = std::abs(value - energy[energy.size() - 2]);
    if (rules.energy_tolerance > 0 && change <= rules.energy_tolerance * std::abs(energy.front())) {
        return true;
    }
    const auto window = static_cast<std::size_t>(rules.stagnation_window);
    if (window > 0 && energy.size() > window) {
        const double before = energy[energy.size() - 1 - window];
        return before - value <= rules.stagnation_tolerance * std::abs(value);
    }
    return false;
}

}  // namespace

FlowResult run_flow(const TriangleMesh& mesh, const Energy& energy, Metric& metric,
                    const StoppingRules& rules,
                    const std::function<bool(const FlowProgress&)>& progress,
                    const StepPolicy& policy, const char* caller, const StepPreparation& prepare) {
    require_valid_mesh(mesh, caller);
    const auto update_metric = [&](const TriangleMesh& current) {
        if (prepare) {
            metric.update_alongside(current, [&] { prepare(current); });
        } else {
            metric.update(current);
        }
    };
    if (rules.max_steps > 0) {  // no step, no metric: a factorization costs several steps
        update_metric(mesh);
    }
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };

    FlowResult result;
    result.mesh = mesh;
    double value = energy.value(mesh);
    result.energy.push_back(value);
    if (!std::isfinite(value)) {
        result.status = FlowStatus::NonFinite;
        result.message = std::string(caller) + ": the energy is not finite at the input";
        return result;
    }
    result.status = FlowStatus::MaxSteps;
    while (result.steps < rules.max_steps) {
        if (value <= rules.target_energy) {
            result.status = FlowStatus::Converged;
            break;
        }
        ProposedStep step;
        try {
            if (result.steps > 0) {
                update_metric(result.mesh);
            }
            step = policy(result.mesh, value);
        } catch (const SolverError& e) {
            result.status = FlowStatus::SolverFailed;
            result.message = e.what();
            break;
        }
        if (!step.next) {
            result.status = step.stop;
            if (!step.message.empty()) {
                result.message = std::string(caller) + ": " + step.message + " at step " +
                                 std::to_string(result.steps + 1);
            }
            break;
        }
        // A policy evaluates the energy only at finite positions (fixed_step() gives NaN
        // otherwise), so the energy alone tells a breakdown.
        if (!std::isfinite(step.value)) {
            result.status = FlowStatus::NonFinite;
            result.message =
                std::string(caller) + ": step " + std::to_string(result.steps + 1) +
                " produced non-finite or diverging positions or energy (time step too large?)";
            break;
        }
        result.mesh = std::move(*step.next);
        value = step.value;
        ++result.steps;
        result.energy.push_back(value);
        if (progress &&
            !progress({result.steps, rules.max_steps, value, elapsed(), &result.mesh})) {
            result.status = FlowStatus::Cancelled;
            break;
        }
        if (settled(rules, result.energy)) {
            result.status = FlowStatus::Converged;
            break;
        }
        if (elapsed() >= rules.max_seconds) {
            result.status = FlowStatus::TimeLimit;
            break;
        }
    }
    result.seconds = elapsed();
    return result;
}

StepPolicy fixed_step(const Energy& energy,
                      const std::function<VertexField(const TriangleMesh&)>& displacement) {
    return [&energy, displacement](const TriangleMesh& current, double) {
        ProposedStep step;
        step.next = current;
        step.next->V += displacement(current);
        step.value = within_coordinate_range(step.next->V) ? energy.value(*step.next) : NAN;
        return step;
    };
}

StoppingRules stopping_rules(const FlowOptions& options, const char* caller) {
    if (!finite_above(options.time_step, 0)) {
        throw InvalidInput(std::string(caller) + ": time_step must be positive and finite, got " +
                           std::to_string(options.time_step));
    }
    if (options.max_steps < 0 || !finite_at_least(options.energy_tolerance, 0) ||
        std::isnan(options.max_seconds) || options.max_seconds <= 0) {
        throw InvalidInput(std::string(caller) +
                           ": need max_steps >= 0, energy_tolerance >= 0 and max_seconds > 0");
    }
    return {.max_steps = options.max_steps,
            .max_seconds = options.max_seconds,
            .energy_tolerance = options.energy_tolerance};
}

}  // namespace detail
}  // namespace genflow
