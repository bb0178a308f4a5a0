// SPDX-License-Identifier: MIT
// The step loop shared by the integrators: stopping rules, energy log, progress, and turning
// breakdowns into a status instead of garbage.
#pragma once

#include <functional>

#include "genflow/energies/energy.h"
#include "genflow/flows/flow.h"
#include "genflow/metrics/metric.h"

namespace genflow::detail {

/// Runs `step` (which returns the displacement to add to V, with `metric` already updated to
/// the current positions) until a stopping rule fires. The first `metric.update()` happens
/// before the loop, so a mesh the metric refuses is an exception, not a status.
FlowResult run_flow(const TriangleMesh& mesh, const Energy& energy, Metric& metric,
                    const FlowOptions& options,
                    const std::function<VertexField(const TriangleMesh&)>& step,
                    const char* caller);

}  // namespace genflow::detail
