// SPDX-License-Identifier: MIT
#pragma once

#include "genflow/energies/energy.h"
#include "genflow/flows/flow.h"
#include "genflow/metrics/metric.h"

namespace genflow {

/// The explicit generalized gradient flow (paper eq. 10):
///
///     X_{t+dt} = X_t − dt·G(X_t)⁻¹ dE/dX(X_t),
///
/// re-assembling the metric at every step. Stable only for small enough dt (for mean-curvature
/// flow dt ≲ h²); see `implicit_euler()` for large steps.
///
/// \throws InvalidInput if the mesh is refused by `metric.update()` or the options are invalid
///         (dt not positive and finite, max_steps < 0). Breakdowns during the flow are reported
///         in the result's status, never thrown.
/// \throws SolverError  if the metric cannot be factored at the input positions.
[[nodiscard]] FlowResult explicit_euler(const TriangleMesh& mesh, const Energy& energy,
                                        Metric& metric, const FlowOptions& options);

}  // namespace genflow
