// SPDX-License-Identifier: MIT
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "genflow/flows/flow.h"
#include "genflow/mesh.h"

namespace genflow {

/// Parameters shared by the smoothing flows. Lengths are relative to the mean edge length h of
/// the input mesh, so the same options mean the same smoothing at any scale and resolution.
struct SmoothingOptions {
    /// Time step in units of h² (the area flows' time has units of length²). Fairing is
    /// unconditionally stable; 0.25–1 removes scanner-like noise of amplitude ~0.4h in a few
    /// steps (see the horse table in docs/benchmarks.md). Mean-curvature flow clamps it to its
    /// stability limit.
    double time_step = 0.5;
    /// Number of steps.
    int steps = 5;
    /// H1/H2 fairing: the metric's λ in units of h²; unset means λ = dt, the paper's implicit
    /// fairing (§4).
    std::optional<double> lambda = std::nullopt;
    /// The metric of the input for every step instead of that of each step's mesh: a flow in one
    /// fixed inner product, as libigl's fairing keeps its cotangent matrix. Fairing (H1, H2) then
    /// factors once and each step costs a solve. The first step is the same either way.
    bool freeze_metric = false;
    /// H2 only: weight μ of the Δ² term in units of h⁴.
    double mu = 1.0;
    /// Volume-controlled fairing only: the volume penalty λ ∈ (0, 1]; the volume loss is about
    /// λ times that of plain fairing (docs/formulas.md §4).
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
/// area in the H1 metric with λ = dt, i.e. (M + dt K) X' = M X at every step. With
/// options.lambda set, the H1 metric uses that λ instead: (M + λK) X' = (M + (λ − dt)K) X.
/// \throws InvalidInput as `mean_curvature_flow()`.
[[nodiscard]] FlowResult implicit_fairing(const TriangleMesh& mesh,
                                          const SmoothingOptions& options);

/// Higher-order fairing: the explicit flow of the area in the H2 metric with λ = dt (or
/// options.lambda·h²) and μ = options.mu·h⁴, i.e. (M + dt K + μ K D⁻¹K) X' = (M + μ K D⁻¹K) X
/// (docs/formulas.md §3).
/// \throws InvalidInput as `mean_curvature_flow()`.
[[nodiscard]] FlowResult higher_order_fairing(const TriangleMesh& mesh,
                                              const SmoothingOptions& options);

/// Volume-controlled implicit fairing (paper §5, eq. 13 as corrected in docs/formulas.md §4): the
/// implicit (eq. 11) flow of the area in the VolumeControlledMetric with λ =
/// options.volume_lambda, i.e. (D B⁻¹ + dt K) X' = D B⁻¹ X. It smooths like implicit fairing
/// while losing about λ times its volume; inward-oriented meshes behave the same.
/// \throws InvalidInput as `mean_curvature_flow()`, or if volume_lambda is not in (0, 1].
[[nodiscard]] FlowResult volume_controlled_fairing(const TriangleMesh& mesh,
                                                   const SmoothingOptions& options);

/// A smoothing flow by the name the command line and Python give it.
struct SmoothingFlow {
    std::string_view name;  ///< "mcf", "fairing", "fairing2" or "volume-fairing"
    FlowResult (*run)(const TriangleMesh&, const SmoothingOptions&);
};

/// Every smoothing flow above, in the order they are declared.
[[nodiscard]] const std::vector<SmoothingFlow>& smoothing_flows();

/// The flow named `name` (SmoothingFlow::name).
/// \throws InvalidInput naming the flows if there is none of that name.
[[nodiscard]] const SmoothingFlow& smoothing_flow(std::string_view name);

}  // namespace genflow
