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

FlowResult run_flow(const TriangleMesh& mesh, const Energy& energy, Metric& metric,
                    const FlowOptions& options,
                    const std::function<VertexField(const TriangleMesh&)>& step,
                    const char* caller) {
    if (!finite_above(options.time_step, 0)) {
        throw InvalidInput(std::string(caller) + ": time_step must be positive and finite, got " +
                           std::to_string(options.time_step));
    }
    if (options.max_steps < 0 || !finite_at_least(options.energy_tolerance, 0) ||
        std::isnan(options.max_seconds) || options.max_seconds <= 0) {
        throw InvalidInput(std::string(caller) +
                           ": need max_steps >= 0, energy_tolerance >= 0 and max_seconds > 0");
    }
    require_valid_mesh(mesh, caller);
    metric.update(mesh);
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };

    FlowResult result;
    result.mesh = mesh;
    result.energy.push_back(energy.value(mesh));
    result.status = FlowStatus::MaxSteps;
    while (result.steps < options.max_steps) {
        TriangleMesh next = result.mesh;
        try {
            if (result.steps > 0) {
                metric.update(result.mesh);
            }
            next.V += step(result.mesh);
        } catch (const SolverError& e) {
            result.status = FlowStatus::SolverFailed;
            result.message = e.what();
            break;
        }
        const double value = all_finite(next.V) ? energy.value(next) : NAN;
        if (!std::isfinite(value)) {
            result.status = FlowStatus::NonFinite;
            result.message = std::string(caller) + ": step " + std::to_string(result.steps + 1) +
                             " produced non-finite positions or energy (time step too large?)";
            break;
        }
        result.mesh = std::move(next);
        ++result.steps;
        result.energy.push_back(value);
        if (options.progress) {
            const FlowProgress progress{result.steps, options.max_steps, value, elapsed(),
                                        &result.mesh};
            if (!options.progress(progress)) {
                result.status = FlowStatus::Cancelled;
                break;
            }
        }
        const double change = std::abs(value - result.energy[result.energy.size() - 2]);
        if (options.energy_tolerance > 0 &&
            change <= options.energy_tolerance * std::abs(result.energy.front())) {
            result.status = FlowStatus::Converged;
            break;
        }
        if (elapsed() >= options.max_seconds) {
            result.status = FlowStatus::TimeLimit;
            break;
        }
    }
    result.seconds = elapsed();
    return result;
}

}  // namespace detail
}  // namespace genflow
