// SPDX-License-Identifier: MIT
#pragma once

#include <functional>
#include <limits>

#include "genflow/energies/energy.h"
#include "genflow/flows/flow.h"
#include "genflow/metrics/metric.h"

namespace genflow {

/// Where a steepest step's backtracking starts (docs/formulas.md §9).
enum class FirstStep {
    /// min(2 τ_previous, cap); after a step that had to backtrack, τ_previous itself
    /// (DescentOptions::double_after_backtracking).
    Doubling,
    /// The τ at which the quadratic that starts as steeply as this step and falls as far as
    /// the last step fell has its minimum: 2 (E_previous − E)/⟨dE, g⟩, capped (Nocedal and
    /// Wright, Numerical Optimization, §3.5). Where the flow slows down smoothly the first τ is
    /// then nearly always taken; where the energy is nearly linear it doubles the decrease, as
    /// Doubling doubles τ.
    LastDecrease,
};

/// Parameters of gradient_descent(). Scale-free use: give max_displacement relative to the
/// shape (docs/formulas.md §9: 2 % of the bounding-box diagonal).
struct DescentOptions {
    /// No vertex moves farther than this in one step (a length, > 0): the step size is capped
    /// at max_displacement / max_i |g_i|, so the cap follows the shape, not the energy's units.
    double max_displacement = 0;
    /// Stop after this many accepted steps.
    int max_steps = 500;
    /// Converged when E fell by less than stagnation_tolerance·|E| over the last
    /// stagnation_window steps (0: never).
    double stagnation_tolerance = 1e-4;
    int stagnation_window = 20;
    /// Converged when E ≤ this (for energies with a known floor, as d_H ≈ 0).
    double target_energy = -std::numeric_limits<double>::infinity();
    /// Stop after this much wall time, checked after every step.
    double max_seconds = std::numeric_limits<double>::infinity();
    /// Implicit steps (paper eq. 11, docs/formulas.md §9): X ← X − τ (G + τA)⁻¹ dE/dX with A from
    /// the energy's linearization (for d_H, A = diag Σ_j c_ij), the same backtracking on τ. As τ
    /// grows the step tends to a prior-regularized projection instead of overshooting, so
    /// steps may be longer. Needs an energy with `linearize()`.
    bool implicit = false;
    /// With FirstStep::Doubling, where τ starts after a step that had to backtrack (its first τ
    /// refused): at twice the τ it took, as after any step (min(2 τ_previous, cap)), or, false,
    /// at that τ itself. Twice over it overshoots again: a quarter more trials (d_H evaluations)
    /// per step for the same results (docs/eval/results.md, "Holding the step after backtracking").
    bool double_after_backtracking = false;
    /// Where an explicit steepest step's τ starts after the first step (which starts at the
    /// cap). Implicit steps double as Doubling does: their direction changes with τ.
    FirstStep first_step = FirstStep::Doubling;
    /// Quasi-Newton steps: L-BFGS with this many past steps, the metric's G⁻¹ its initial
    /// inverse Hessian (docs/formulas.md §9). The step is X ← X − τ H dE/dX from τ = 1, within
    /// the same displacement cap and Armijo backtracking; a direction that does not descend
    /// clears the memory and the steepest step is taken. 0: steepest descent alone. Not with
    /// `implicit`.
    int quasi_newton_memory = 0;
    /// Called after every accepted step; return false to stop (status Cancelled). Optional.
    std::function<bool(const FlowProgress&)> progress = {};
};

/// Steepest descent in the metric with Armijo backtracking (docs/formulas.md §9): g = G⁻¹ dE/dX,
/// X ← X − τ g, where τ starts at min(2 τ_previous, cap), or at τ_previous after a step that
/// backtracked (DescentOptions::double_after_backtracking), or, with FirstStep::LastDecrease, at
/// min(2 (E_previous − E)/⟨dE, g⟩, cap) (DescentOptions::first_step), and is halved until
/// E(X − τ g) ≤ E(X) − 10⁻⁴ τ ⟨dE, g⟩; the energy therefore decreases at every step. The
/// metric is updated at every accepted position. This is the explicit flow of eq. 10 with an
/// adaptive time step, for energies whose stiffness is unknown in advance (the
/// pseudo-Hausdorff distance of shape matching).
///
/// Status: Converged when no step of at least 2⁻⁴⁰ cap decreases E, on stagnation, or at the
/// target energy; otherwise as FlowStatus says.
///
/// \throws InvalidInput if the options are invalid (max_displacement not positive and finite,
///         max_steps < 0, a negative tolerance or window, max_seconds ≤ 0, a negative
///         quasi_newton_memory or one with `implicit`), the metric
///         refuses the mesh, or `implicit` is set for an energy without a linearization.
/// \throws SolverError  if the metric cannot be factored at the input positions.
[[nodiscard]] FlowResult gradient_descent(const TriangleMesh& mesh, const Energy& energy,
                                          Metric& metric, const DescentOptions& options);

}  // namespace genflow
