// SPDX-License-Identifier: MIT
#include "genflow/flows/gradient_descent.h"

#include <chrono>
#include <cmath>
#include <optional>
#include <string>

#include "genflow/exceptions.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

constexpr double kArmijo = 1e-4;
constexpr int kMaxHalvings = 40;
// Implicit steps may grow past the explicit cap, but not without bound: τ doubling at every
// accepted step would overflow after ~1000 steps.
constexpr double kImplicitGrowth = 1e6;

void check_options(const DescentOptions& options) {
    if (!detail::finite_above(options.max_displacement, 0)) {
        throw InvalidInput("gradient_descent: max_displacement must be positive and finite, got " +
                           std::to_string(options.max_displacement));
    }
    if (options.max_steps < 0 || !detail::finite_at_least(options.stagnation_tolerance, 0) ||
        options.stagnation_window < 0 || std::isnan(options.max_seconds) ||
        options.max_seconds <= 0 || std::isnan(options.target_energy)) {
        throw InvalidInput(
            "gradient_descent: need max_steps >= 0, stagnation_tolerance >= 0, "
            "stagnation_window >= 0, max_seconds > 0 and a target energy that is not NaN");
    }
}

}  // namespace

FlowResult gradient_descent(const TriangleMesh& mesh, const Energy& energy, Metric& metric,
                            const DescentOptions& options) {
    check_options(options);
    detail::require_valid_mesh(mesh, "gradient_descent");
    metric.update(mesh);
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
        result.message = "gradient_descent: the energy is not finite at the input";
        return result;
    }
    result.status = FlowStatus::MaxSteps;
    double step_size = 0;      // τ of the last accepted step; 0 before the first
    bool backtracked = false;  // whether that step's first τ was refused
    while (result.steps < options.max_steps) {
        if (value <= options.target_energy) {
            result.status = FlowStatus::Converged;
            break;
        }
        VertexField differential;
        VertexField g;  // the explicit gradient G⁻¹ dE/dX
        double slope = 0;
        std::optional<Linearization> linearization;
        try {
            if (result.steps > 0) {
                metric.update(result.mesh);
            }
            differential = energy.differential(result.mesh);
            g = metric.gradient(differential);
            slope = (differential.array() * g.array()).sum();  // ‖g‖²_G
            if (options.implicit) {
                linearization = energy.linearize(result.mesh);
                if (!linearization) {
                    throw InvalidInput(
                        "gradient_descent: implicit steps need an energy with linearize()");
                }
            }
        } catch (const SolverError& e) {
            result.status = FlowStatus::SolverFailed;
            result.message = e.what();
            break;
        }
        const double largest = g.rowwise().norm().maxCoeff();
        if (!std::isfinite(slope) || !std::isfinite(largest)) {
            result.status = FlowStatus::NonFinite;
            result.message =
                "gradient_descent: non-finite gradient at step " + std::to_string(result.steps + 1);
            break;
        }
        if (!(slope > 0) || !(largest > 0)) {
            result.status = FlowStatus::Converged;  // a stationary point
            break;
        }
        // Explicit: the direction is g for every τ, capped so no vertex moves farther than
        // max_displacement. Implicit: the direction (G + τA)⁻¹ dE/dX depends on τ and shrinks
        // as τ grows, so τ may grow past the explicit cap; the displacement is checked per τ.
        const double cap = options.max_displacement / largest;
        const double longest_tau = options.implicit ? kImplicitGrowth * cap : cap;
        // Twice the last τ after a step taken at once; after one that had to backtrack, the τ
        // it took, which twice over overshot (DescentOptions::double_after_backtracking).
        const double growth = backtracked && !options.double_after_backtracking ? 1 : 2;
        double tau = step_size > 0 ? std::min(growth * step_size, longest_tau) : cap;
        TriangleMesh trial = result.mesh;
        bool accepted = false;
        double trial_value = value;
        int halving = 0;
        for (; halving <= kMaxHalvings; ++halving, tau /= 2) {
            VertexField direction = g;
            double decrease = slope;
            if (options.implicit) {
                try {
                    direction = metric.shifted_gradient(linearization->A, tau, differential);
                } catch (const SolverError&) {
                    continue;  // a smaller τ is closer to the explicit step
                }
                decrease = (differential.array() * direction.array()).sum();
                if (!(tau * direction.rowwise().norm().maxCoeff() <= options.max_displacement) ||
                    !(decrease > 0)) {
                    continue;
                }
            }
            trial.V = result.mesh.V - tau * direction;
            trial_value = energy.value(trial);
            // Strictly lower, too: a step too small to change E in floating point is no step.
            if (std::isfinite(trial_value) && trial_value <= value - kArmijo * tau * decrease &&
                trial_value < value) {
                accepted = true;
                break;
            }
        }
        if (!accepted) {
            result.status = FlowStatus::Converged;  // no descent left at this resolution
            break;
        }
        step_size = tau;
        backtracked = halving > 0;
        result.mesh = std::move(trial);
        value = trial_value;
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
        const int window = options.stagnation_window;
        if (window > 0 && result.steps >= window) {
            const double before = result.energy[result.energy.size() - 1 - window];
            if (before - value <= options.stagnation_tolerance * std::abs(value)) {
                result.status = FlowStatus::Converged;
                break;
            }
        }
        if (elapsed() >= options.max_seconds) {
            result.status = FlowStatus::TimeLimit;
            break;
        }
    }
    result.seconds = elapsed();
    return result;
}

}  // namespace genflow
