// SPDX-License-Identifier: MIT
#pragma once

#include "genflow/energies/energy.h"
#include "genflow/flows/flow.h"
#include "genflow/metrics/metric.h"

namespace genflow {

/// The linearized implicit generalized gradient flow (paper eq. 11): with the energy's
/// linearization dE/dX ≈ A X + B frozen at X_t,
///
///     (G + dt·A) X_{t+dt} = G X_t − dt·B,
///
/// solved as X_{t+dt} = X_t − dt·(G + dt·A)⁻¹(A X_t + B) (`Metric::shifted_gradient()`).
/// Stable for large dt because A is PSD.
///
/// \throws InvalidInput if the energy has no linearization, the mesh is refused by
///         `metric.update()`, or the options are invalid. Breakdowns during the flow are reported
///         in the result's status, never thrown.
/// \throws SolverError  if the metric cannot be factored at the input positions.
[[nodiscard]] FlowResult implicit_euler(const TriangleMesh& mesh, const Energy& energy,
                                        Metric& metric, const FlowOptions& options);

}  // namespace genflow
