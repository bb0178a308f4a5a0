// SPDX-License-Identifier: MIT
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "genflow/mesh.h"

namespace genflow {

/// Why a flow ended.
enum class FlowStatus {
    Converged,     ///< the relative energy change fell below FlowOptions::energy_tolerance
    MaxSteps,      ///< FlowOptions::max_steps were taken
    TimeLimit,     ///< FlowOptions::max_seconds elapsed
    Cancelled,     ///< the progress callback returned false
    NonFinite,     ///< a step produced NaN or Inf; the last finite mesh is returned
    SolverFailed,  ///< a metric could not be factored or solved; the last mesh is returned
};

/// A short name for a status ("converged", "max-steps", ...), as printed by the CLI.
[[nodiscard]] const char* to_string(FlowStatus status);

/// What the progress callback sees after every step.
struct FlowProgress {
    int step = 0;  ///< steps taken so far
    int max_steps = 0;
    double energy = 0;                   ///< E after this step
    double seconds = 0;                  ///< wall time since the flow started
    const TriangleMesh* mesh = nullptr;  ///< the current positions (valid during the call)
};

/// Parameters shared by the integrators.
struct FlowOptions {
    /// Time step dt > 0, in the units of the energy and metric (for the area in L2 or H1:
    /// length²). The smoothing functions convert their scale-free step to this.
    double time_step = 0;
    /// Stop after this many steps.
    int max_steps = 100;
    /// Stop when |E_k − E_{k−1}| ≤ energy_tolerance·|E_0| (0: never).
    double energy_tolerance = 0;
    /// Stop after this much wall time, checked after every step.
    double max_seconds = std::numeric_limits<double>::infinity();
    /// Called after every step; return false to stop (status Cancelled). Optional.
    std::function<bool(const FlowProgress&)> progress = {};
};

/// What a flow produced.
struct FlowResult {
    TriangleMesh mesh;  ///< the final positions (same connectivity as the input)
    FlowStatus status = FlowStatus::MaxSteps;
    int steps = 0;               ///< steps actually taken
    std::vector<double> energy;  ///< E_0, E_1, ..., E_steps
    double seconds = 0;          ///< wall time
    std::string message;         ///< why it stopped, for NonFinite and SolverFailed

    /// Whether the energy ended above where it started: a descent that diverged (a time step too
    /// large for the metric), whatever the status says.
    [[nodiscard]] bool energy_rose() const {
        return energy.size() > 1 && energy.back() > energy.front();
    }

    /// True unless the flow broke down (NonFinite or SolverFailed).
    [[nodiscard]] bool ok() const {
        return status != FlowStatus::NonFinite && status != FlowStatus::SolverFailed;
    }
};

}  // namespace genflow
