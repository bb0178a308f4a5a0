// SPDX-License-Identifier: MIT
#pragma once

#include "genflow/flows/flow.h"
#include "genflow/mesh.h"

namespace genflow {

/// Parameters shared by the smoothing flows. Lengths are relative to the mean edge length h of
/// the input mesh, so the same options mean the same smoothing at any scale and resolution.
struct SmoothingOptions {
    /// Time step in units of h² (the area flows' time has units of length²). Fairing is
    /// unconditionally stable, so 1–100 are sensible; mean-curvature flow clamps it to its
    /// stability limit.
    double time_step = 1.0;
    /// Number of steps.
    int steps = 10;
    /// H2 only: weight μ of the Δ² term in units of h⁴.
    double mu = 1.0;
    /// Volume-controlled fairing only: the volume penalty λ ∈ (0, 1]; the volume loss is about
    /// λ times that of plain fairing (SPEC.md §4).
    double volume_lambda = 0.05;
    /// Keep the boundary vertices where they are.
    bool fix_boundary = false;
    /// Called after every step; return false to stop. Optional.
    std::function<bool(const FlowProgress&)> progress = {};
};

/// Mean-curvature flow: the explicit L2 gradient flow of the area (paper §2), with the Voronoi
/// lumped mass so the velocity is the mean-curvature normal −2Hn. The time step is clamped to
/// 0.9× the explicit stability bound 2/max_i(Σ_j|K_ij|/m_i) (Gershgorin), evaluated on the input
/// mesh; the result's status says if the flow still broke down.
/// \throws InvalidInput if the mesh is refused (see `validate()`) or the options are invalid.
[[nodiscard]] FlowResult mean_curvature_flow(const TriangleMesh& mesh,
                                             const SmoothingOptions& options);

/// Implicit fairing [Desbrun et al. 1999] as the paper derives it (§4): the explicit flow of the
/// area in the H1 metric with λ = dt, i.e. (M + dt K) X' = M X at every step.
/// \throws InvalidInput as `mean_curvature_flow()`.
[[nodiscard]] FlowResult implicit_fairing(const TriangleMesh& mesh,
                                          const SmoothingOptions& options);

/// Higher-order fairing: the explicit flow of the area in the H2 metric with λ = dt and
/// μ = options.mu·h⁴, i.e. (M + dt K + μ K D⁻¹K) X' = (M + μ K D⁻¹K) X (SPEC.md §3).
/// \throws InvalidInput as `mean_curvature_flow()`.
[[nodiscard]] FlowResult higher_order_fairing(const TriangleMesh& mesh,
                                              const SmoothingOptions& options);

}  // namespace genflow
