// SPDX-License-Identifier: MIT
#include "genflow/metrics/l2_metric.h"

#include "metrics/metric_support.h"

namespace genflow {

Eigen::SparseMatrix<double> L2Metric::assemble(const TriangleMesh& mesh) const {
    return detail::floored_mass_matrix(mesh, options_.mass);
}

}  // namespace genflow
