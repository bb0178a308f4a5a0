// SPDX-License-Identifier: MIT
// The step loop shared by the integrators: stopping rules, energy log, progress, and turning
// breakdowns into a status instead of garbage.
#pragma once

#include <functional>

#include "genflow/energies/energy.h"
#include "genflow/flows/flow.h"

namespace genflow::detail {

/// Runs `step` (which returns the displacement to add to V) until a stopping rule fires.
FlowResult run_flow(const TriangleMesh& mesh, const Energy& energy, const FlowOptions& options,
                    const std::function<VertexField(const TriangleMesh&)>& step,
                    const char* caller);

}  // namespace genflow::detail
