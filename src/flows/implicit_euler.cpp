// SPDX-License-Identifier: MIT
#include "genflow/flows/implicit_euler.h"

#include "flows/flow_loop.h"
#include "genflow/exceptions.h"

namespace genflow {

FlowResult implicit_euler(const TriangleMesh& mesh, const Energy& energy, Metric& metric,
                          const FlowOptions& options) {
    return detail::run_flow(
        mesh, energy, metric, detail::stopping_rules(options, "implicit_euler"), options.progress,
        detail::fixed_step(
            energy,
            [&](const TriangleMesh& current) -> VertexField {
                const auto linearization = energy.linearize(current);
                if (!linearization) {
                    throw InvalidInput(
                        "implicit_euler: the energy has no linearization; use explicit_euler");
                }
                const VertexField R = linearization->A * current.V + linearization->B;
                return -options.time_step *
                       metric.shifted_gradient(linearization->A, options.time_step, R);
            }),
        "implicit_euler");
}

}  // namespace genflow
