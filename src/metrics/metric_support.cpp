// SPDX-License-Identifier: MIT
#include "metrics/metric_support.h"

namespace genflow::detail {

namespace {
double mass_floor(const Eigen::VectorXd& diagonal) {
    return diagonal.size() > 0 ? 1e-10 * diagonal.mean() : 0.0;
}
}  // namespace

Eigen::SparseMatrix<double> floored_mass_matrix(const TriangleMesh& mesh, MassType type) {
    Eigen::SparseMatrix<double> M = mass_matrix(mesh, type);
    Eigen::VectorXd diagonal = M.diagonal();
    const double floor = mass_floor(diagonal);
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
        if (diagonal[i] < floor) {
            M.coeffRef(i, i) = floor;
        }
    }
    M.makeCompressed();
    return M;
}

Eigen::VectorXd floored_lumped_masses(const TriangleMesh& mesh, MassType type) {
    Eigen::VectorXd masses = lumped_masses(mesh, type);
    return masses.cwiseMax(mass_floor(masses));
}

}  // namespace genflow::detail
