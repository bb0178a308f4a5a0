// SPDX-License-Identifier: MIT
#include "genflow/evaluation/single_view.h"

#include <cmath>
#include <random>

#include "genflow/exceptions.h"
#include "genflow/mesh/face_selection.h"
#include "genflow/operators/normals.h"
#include "operators/triangle.h"

namespace genflow {

TriangleMesh single_view(const TriangleMesh& mesh, const Eigen::Vector3d& view) {
    detail::require_valid_mesh(mesh, "single_view");
    if (!detail::all_finite(view) || view.norm() == 0) {
        throw InvalidInput("single_view: the view direction must be finite and non-zero");
    }
    const Eigen::VectorXd facing = face_normals(mesh) * view;
    return {mesh.V, faces_where(mesh.F, [&](Eigen::Index f) { return facing[f] < 0; })};
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
