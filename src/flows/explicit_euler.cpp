// SPDX-License-Identifier: MIT
#include "genflow/flows/explicit_euler.h"

#include "flows/flow_loop.h"

namespace genflow {

FlowResult explicit_euler(const TriangleMesh& mesh, const Energy& energy, Metric& metric,
                          const FlowOptions& options) {
    metric.update(mesh);  // refuse a bad mesh up front, as an exception
    bool first = true;
    return detail::run_flow(
        mesh, energy, options,
        [&](const TriangleMesh& current) -> VertexField {
            if (!first) {
                metric.update(current);
            }
            first = false;
            return -options.time_step * metric.gradient(energy.differential(current));
        },
        "explicit_euler");
}

}  // namespace genflow
