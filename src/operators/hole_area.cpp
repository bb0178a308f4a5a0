// SPDX-License-Identifier: MIT
#include "genflow/operators/hole_area.h"

#include <vector>

#include "genflow/mesh/edges.h"
#include "mesh/union_find.h"
#include "operators/triangle.h"

namespace genflow {

double hole_area(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "hole_area");
    const Eigen::MatrixX2i boundary = oriented_boundary_edges(mesh.F);
    detail::UnionFind loops(static_cast<std::size_t>(mesh.V.rows()));
    for (Eigen::Index e = 0; e < boundary.rows(); ++e) {
        loops.unite(static_cast<std::size_t>(boundary(e, 0)),
                    static_cast<std::size_t>(boundary(e, 1)));
    }
    // The centroid of each loop's edge starts first: about it, round-off stays at the hole's
    // scale, not the mesh's distance from the origin.
    const auto n = static_cast<std::size_t>(mesh.V.rows());
    std::vector<Eigen::Vector3d> centre(n, Eigen::Vector3d::Zero());
    std::vector<double> count(n, 0);
    for (Eigen::Index e = 0; e < boundary.rows(); ++e) {
        const std::size_t loop = loops.find(static_cast<std::size_t>(boundary(e, 0)));
        centre[loop] += mesh.V.row(boundary(e, 0)).transpose();
        count[loop] += 1;
    }
    std::vector<Eigen::Vector3d> vector_area(n, Eigen::Vector3d::Zero());
    for (Eigen::Index e = 0; e < boundary.rows(); ++e) {
        const std::size_t loop = loops.find(static_cast<std::size_t>(boundary(e, 0)));
        const Eigen::Vector3d c = centre[loop] / count[loop];
        const Eigen::Vector3d a = mesh.V.row(boundary(e, 0)).transpose() - c;
        const Eigen::Vector3d b = mesh.V.row(boundary(e, 1)).transpose() - c;
        vector_area[loop] += a.cross(b) / 2;
    }
    double area = 0;
    for (const Eigen::Vector3d& v : vector_area) {
        area += v.norm();
    }
    return area;
}

}  // namespace genflow
