// SPDX-License-Identifier: MIT
#include "genflow/flows/explicit_euler.h"

#include "flows/flow_loop.h"

namespace genflow {

FlowResult explicit_euler(const TriangleMesh& mesh, const Energy& energy, Metric& metric,
                          const FlowOptions& options) {
    // dE/dX at the current mesh, computed while the metric updates to it: a smoothing flow's
    // factorization in two halves leaves a thread idle for longer than the area's gradient takes.
    VertexField differential;
    return detail::run_flow(
        mesh, energy, metric, detail::stopping_rules(options, "explicit_euler"), options.progress,
        detail::fixed_step(energy,
                           [&](const TriangleMesh&) -> VertexField {
                               return -options.time_step * metric.gradient(differential);
                           }),
        "explicit_euler",
        [&](const TriangleMesh& current) { differential = energy.differential(current); });
}

}  // namespace genflow
