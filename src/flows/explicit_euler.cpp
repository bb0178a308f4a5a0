// SPDX-License-Identifier: MIT
#include "genflow/flows/explicit_euler.h"

#include "flows/flow_loop.h"

namespace genflow {

FlowResult explicit_euler(const TriangleMesh& mesh, const Energy& energy, Metric& metric,
                          const FlowOptions& options) {
    return detail::run_flow(
        mesh, energy, metric, detail::stopping_rules(options, "explicit_euler"), options.progress,
        detail::fixed_step(energy,
                           [&](const TriangleMesh& current) -> VertexField {
                               return -options.time_step *
                                      metric.gradient(energy.differential(current));
                           }),
        "explicit_euler");
}

}  // namespace genflow
