// SPDX-License-Identifier: MIT
#include "genflow/operators/hole_area.h"

#include <vector>

#include "genflow/mesh/boundary_loops.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

// ½ Σ (x_a − c) × (x_b − c) over the loop's edges a → b, about its centroid c: round-off stays
// at the hole's scale, not the mesh's distance from the origin.
Eigen::Vector3d vector_area(const Eigen::MatrixX3d& V, const std::vector<int>& loop) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const int v : loop) {
        centre += V.row(v).transpose();
    }
    centre /= static_cast<double>(loop.size());
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < loop.size(); ++k) {
        const Eigen::Vector3d a = V.row(loop[k]).transpose() - centre;
        const Eigen::Vector3d b = V.row(loop[(k + 1) % loop.size()]).transpose() - centre;
        sum += a.cross(b);
    }
    return sum / 2;
}

}  // namespace

double hole_area(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "hole_area");
    double area = 0;
    for (const std::vector<int>& loop : boundary_loops(mesh)) {
        area += vector_area(mesh.V, loop).norm();
    }
    return area;
}

}  // namespace genflow
