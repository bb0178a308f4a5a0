// SPDX-License-Identifier: MIT
#include "genflow/flows/gradient_descent.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "flows/flow_loop.h"
#include "flows/quasi_newton_memory.h"
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
    if (options.quasi_newton_memory < 0 || (options.quasi_newton_memory > 0 && options.implicit)) {
        throw InvalidInput(
            "gradient_descent: quasi_newton_memory must be >= 0, and 0 with implicit steps, got " +
            std::to_string(options.quasi_newton_memory));
    }
    if (options.max_steps < 0 || !detail::finite_at_least(options.stagnation_tolerance, 0) ||
        options.stagnation_window < 0 || std::isnan(options.max_seconds) ||
        options.max_seconds <= 0 || std::isnan(options.target_energy)) {
        throw InvalidInput(
            "gradient_descent: need max_steps >= 0, stagnation_tolerance >= 0, "
            "stagnation_window >= 0, max_seconds > 0 and a target energy that is not NaN");
    }
}

// The line-search policy: steepest descent in the metric, τ from the last accepted step
// (DescentOptions::first_step), halved until the Armijo condition holds; with a quasi-Newton
// memory, its direction first, from τ = 1 (DescentOptions::quasi_newton_memory).
class LineSearch {
public:
    LineSearch(const Energy& energy, Metric& metric, const DescentOptions& options)
        : energy_(energy), metric_(metric), options_(options) {
        if (options.quasi_newton_memory > 0) {
            memory_.emplace(options.quasi_newton_memory);
        }
    }

    detail::ProposedStep operator()(const TriangleMesh& current, double value) {
        const VertexField differential = energy_.differential(current);
        if (memory_) {
            memory_->record(current.V, differential, metric_);
        }
        const VertexField g = metric_.gradient(differential);           // the explicit gradient
        const double slope = (differential.array() * g.array()).sum();  // ‖g‖²_G
        const double largest = g.rowwise().norm().maxCoeff();
        if (!std::isfinite(slope) || !std::isfinite(largest)) {
            return {.stop = FlowStatus::NonFinite, .message = "non-finite gradient"};
        }
        if (!(slope > 0) || !(largest > 0)) {
            return {};  // a stationary point: Converged
        }
        if (memory_ && !memory_->empty()) {
            if (std::optional<detail::ProposedStep> step =
                    quasi_newton_step(current, value, differential)) {
                return std::move(*step);
            }
            memory_->clear();  // its direction did not descend: the metric's gradient instead
        }
        // τ at which the steepest step moves a vertex by max_displacement.
        const double cap = options_.max_displacement / largest;
        return options_.implicit ? implicit_step(current, value, differential, cap)
                                 : explicit_step(current, value, g, slope, cap);
    }

private:
    struct AcceptedStep {
        detail::ProposedStep step;
        double tau = 0;
        int halvings = 0;
    };

    // Armijo's condition for a step whose first-order decrease is `decrease`; strictly lower,
    // too: a step too small to change E in floating point is no step.
    static bool accepts(double trial_value, double value, double decrease) {
        return std::isfinite(trial_value) && trial_value <= value - kArmijo * decrease &&
               trial_value < value;
    }

    // The step current − τ·direction for the first of τ, τ/2, … that Armijo's condition
    // accepts, `decrease` being the first-order decrease per unit τ; none if no τ is accepted.
    [[nodiscard]] std::optional<AcceptedStep> backtrack(const TriangleMesh& current, double value,
                                                        const VertexField& direction,
                                                        double decrease, double tau) const {
        TriangleMesh trial = current;
        for (int halving = 0; halving <= kMaxHalvings; ++halving, tau /= 2) {
            trial.V = current.V - tau * direction;
            // Beyond the coordinates operators take the step has diverged: halve it.
            const double trial_value =
                detail::within_coordinate_range(trial.V) ? energy_.value(trial) : NAN;
            if (accepts(trial_value, value, tau * decrease)) {
                return AcceptedStep{{.next = std::move(trial), .value = trial_value}, tau, halving};
            }
        }
        return std::nullopt;
    }

    // The first τ of a steepest step: twice the last τ after a step taken at once; after one
    // that had to backtrack, the τ it took, which twice over overshot
    // (DescentOptions::double_after_backtracking). `cap` before the first step.
    [[nodiscard]] double first_tau(double longest_tau, double cap) const {
        const double growth = backtracked_ && !options_.double_after_backtracking ? 1 : 2;
        return step_size_ > 0 ? std::min(growth * step_size_, longest_tau) : cap;
    }

    // The first τ of an explicit steepest step of slope ⟨dE, g⟩ (DescentOptions::first_step):
    // where the quadratic through the last step's decrease has its minimum, 2 ΔE/slope; `cap`
    // before the first step.
    [[nodiscard]] double first_explicit_tau(double slope, double cap) const {
        if (options_.first_step == FirstStep::LastDecrease && last_decrease_ > 0) {
            return std::min(2 * last_decrease_ / slope, cap);
        }
        return first_tau(cap, cap);
    }

    void remember(double tau, int halvings) {
        step_size_ = tau;
        backtracked_ = halvings > 0;
    }

    // Explicit: the direction is g for every τ, capped so that no vertex moves farther than
    // max_displacement.
    detail::ProposedStep explicit_step(const TriangleMesh& current, double value,
                                       const VertexField& g, double slope, double cap) {
        std::optional<AcceptedStep> accepted =
            backtrack(current, value, g, slope, first_explicit_tau(slope, cap));
        if (!accepted) {
            return {};  // no descent left at this resolution: Converged
        }
        last_decrease_ = value - accepted->step.value;
        remember(accepted->tau, accepted->halvings);
        return std::move(accepted->step);
    }

    // Implicit (eq. 11): the direction (G + τA)⁻¹ dE/dX depends on τ and shrinks as τ grows, so
    // τ may grow past the explicit cap; the displacement is checked per τ.
    detail::ProposedStep implicit_step(const TriangleMesh& current, double value,
                                       const VertexField& differential, double cap) {
        const std::optional<Linearization> linearization = energy_.linearize(current);
        if (!linearization) {
            throw InvalidInput("gradient_descent: implicit steps need an energy with linearize()");
        }
        double tau = first_tau(kImplicitGrowth * cap, cap);
        TriangleMesh trial = current;
        for (int halving = 0; halving <= kMaxHalvings; ++halving, tau /= 2) {
            VertexField direction;
            try {
                direction = metric_.shifted_gradient(linearization->A, tau, differential);
            } catch (const SolverError&) {
                continue;  // a smaller τ is closer to the explicit step
            }
            const double decrease = (differential.array() * direction.array()).sum();
            if (!(tau * direction.rowwise().norm().maxCoeff() <= options_.max_displacement) ||
                !(decrease > 0)) {
                continue;
            }
            trial.V = current.V - tau * direction;
            // Beyond the coordinates operators take the step has diverged: halve it.
            const double trial_value =
                detail::within_coordinate_range(trial.V) ? energy_.value(trial) : NAN;
            if (accepts(trial_value, value, tau * decrease)) {
                remember(tau, halving);
                return {.next = std::move(trial), .value = trial_value};
            }
        }
        return {};  // no descent left at this resolution: Converged
    }

    // The step along the memory's direction d: τ = 1 is the quasi-Newton step, capped so that
    // no vertex moves farther than max_displacement, and halved until Armijo's condition holds.
    // None if d does not descend or no τ is accepted.
    std::optional<detail::ProposedStep> quasi_newton_step(const TriangleMesh& current, double value,
                                                          const VertexField& differential) {
        const VertexField direction = memory_->direction(differential, metric_);
        const double decrease = (differential.array() * direction.array()).sum();
        const double largest = direction.rowwise().norm().maxCoeff();
        if (!std::isfinite(decrease) || !(decrease > 0) || !std::isfinite(largest) ||
            !(largest > 0)) {
            return std::nullopt;
        }
        std::optional<AcceptedStep> accepted =
            backtrack(current, value, direction, decrease,
                      std::min(1.0, options_.max_displacement / largest));
        if (!accepted) {
            return std::nullopt;
        }
        return std::move(accepted->step);
    }

    const Energy& energy_;
    Metric& metric_;
    const DescentOptions& options_;
    double last_decrease_ = 0;  // how far the last explicit steepest step lowered E; 0 before
    double step_size_ = 0;      // τ of the last accepted steepest step; 0 before the first
    bool backtracked_ = false;  // whether that step's first τ was refused
    std::optional<detail::QuasiNewtonMemory> memory_;  // with quasi_newton_memory > 0
};

}  // namespace

FlowResult gradient_descent(const TriangleMesh& mesh, const Energy& energy, Metric& metric,
                            const DescentOptions& options) {
    check_options(options);
    const detail::StoppingRules rules{.max_steps = options.max_steps,
                                      .max_seconds = options.max_seconds,
                                      .target_energy = options.target_energy,
                                      .stagnation_tolerance = options.stagnation_tolerance,
                                      .stagnation_window = options.stagnation_window};
    return detail::run_flow(mesh, energy, metric, rules, options.progress,
                            LineSearch(energy, metric, options), "gradient_descent");
}

}  // namespace genflow
