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

void pin_fixed(Eigen::SparseMatrix<double>& S, const std::vector<bool>& fixed) {
    if (fixed.empty()) {
        return;
    }
    for (Eigen::Index col = 0; col < S.outerSize(); ++col) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(S, col); it; ++it) {
            if (fixed[static_cast<std::size_t>(it.row())] ||
                fixed[static_cast<std::size_t>(it.col())]) {
                it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
            }
        }
    }
}

VertexField zero_fixed_rows(VertexField field, const std::vector<bool>& fixed) {
    for (std::size_t i = 0; i < fixed.size(); ++i) {
        if (fixed[i]) {
            field.row(static_cast<Eigen::Index>(i)).setZero();
        }
    }
    return field;
}

void copy_fixed_rows(VertexField& result, const VertexField& input,
                     const std::vector<bool>& fixed) {
    for (std::size_t i = 0; i < fixed.size(); ++i) {
        if (fixed[i]) {
            result.row(static_cast<Eigen::Index>(i)) = input.row(static_cast<Eigen::Index>(i));
        }
    }
}

using RowField = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

Eigen::VectorXd interleave(const VertexField& field) {
    const RowField rows = field;
    return Eigen::Map<const Eigen::VectorXd>(rows.data(), rows.size());
}

VertexField deinterleave(const Eigen::VectorXd& vector) {
    return Eigen::Map<const RowField>(vector.data(), vector.size() / 3, 3);
}

}  // namespace genflow::detail
