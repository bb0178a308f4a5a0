// SPDX-License-Identifier: MIT
#include "genflow/operators/heat_kernel_signature.h"

#include <cmath>
#include <string>

#include "genflow/exceptions.h"
#include "operators/triangle.h"

namespace genflow {

std::vector<double> default_heat_kernel_times() {
    return {5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2};
}

Eigen::MatrixXd heat_kernel_signature(const TriangleMesh& mesh,
                                      const std::vector<double>& relative_times) {
    return heat_kernel_signature(laplacian_eigenbasis(mesh), relative_times);
}

Eigen::MatrixXd heat_kernel_signature(const LaplacianEigenbasis& basis,
                                      const std::vector<double>& relative_times) {
    for (const double t : relative_times) {
        if (!detail::finite_above(t, 0)) {
            throw InvalidInput("heat_kernel_signature: times must be positive and finite");
        }
    }
    const double area = basis.masses.sum();
    if (!(area > 0)) {
        throw InvalidInput("heat_kernel_signature: the mesh has zero area");
    }
    const Eigen::MatrixXd squared_functions = basis.functions.array().square().matrix();
    Eigen::MatrixXd signature(basis.functions.rows(),
                              static_cast<Eigen::Index>(relative_times.size()));
    for (std::size_t s = 0; s < relative_times.size(); ++s) {
        const Eigen::VectorXd decay =
            (-basis.values * (relative_times[s] * area)).array().exp().matrix();
        signature.col(static_cast<Eigen::Index>(s)) =
            squared_functions * decay * (area / decay.sum());
    }
    return signature;
}

}  // namespace genflow
