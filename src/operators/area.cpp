// SPDX-License-Identifier: MIT
#include "genflow/operators/area.h"

#include "operators/triangle.h"

namespace genflow {

Eigen::VectorXd face_areas(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "face_areas");
    Eigen::VectorXd areas(mesh.F.rows());
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        areas[f] = detail::Triangle(mesh, f).area();
    }
    return areas;
}

double surface_area(const TriangleMesh& mesh) {
    return face_areas(mesh).sum();
}

VertexField surface_area_gradient(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "surface_area_gradient");
    VertexField gradient = VertexField::Zero(mesh.V.rows(), 3);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const detail::Triangle t(mesh, f);
        if (t.degenerate()) {
            continue;
        }
        const Eigen::Vector3d normal = t.cross / t.double_area;
        for (int k = 0; k < 3; ++k) {
            gradient.row(mesh.F(f, k)) += 0.5 * normal.cross(t.opposite_edge(k)).transpose();
        }
    }
    return gradient;
}

}  // namespace genflow
