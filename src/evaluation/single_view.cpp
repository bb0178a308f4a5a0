// SPDX-License-Identifier: MIT
#include "genflow/evaluation/single_view.h"

#include <cmath>
#include <random>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/operators/normals.h"
#include "operators/triangle.h"

namespace genflow {

TriangleMesh single_view(const TriangleMesh& mesh, const Eigen::Vector3d& view) {
    detail::require_valid_mesh(mesh, "single_view");
    if (!detail::all_finite(view) || view.norm() == 0) {
        throw InvalidInput("single_view: the view direction must be finite and non-zero");
    }
    const Eigen::VectorXd facing = face_normals(mesh) * view;
    std::vector<Eigen::Index> kept;
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        if (facing[f] < 0) {
            kept.push_back(f);
        }
    }
    TriangleMesh seen{mesh.V, Eigen::MatrixX3i(static_cast<Eigen::Index>(kept.size()), 3)};
    for (std::size_t k = 0; k < kept.size(); ++k) {
        seen.F.row(static_cast<Eigen::Index>(k)) = mesh.F.row(kept[k]);
    }
    return seen;
}

Eigen::Vector3d view_direction(std::uint64_t seed) {
    // Three independent normal deviates point uniformly on the sphere.
    std::mt19937_64 random(seed);
    std::normal_distribution<double> normal;
    Eigen::Vector3d direction;
    do {
        direction = {normal(random), normal(random), normal(random)};
    } while (direction.norm() < 1e-9);
    return direction.normalized();
}

}  // namespace genflow
