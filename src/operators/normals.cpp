// SPDX-License-Identifier: MIT
#include "genflow/operators/normals.h"

#include "operators/triangle.h"

namespace genflow {

Eigen::MatrixX3d face_normals(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "face_normals");
    Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(mesh.F.rows(), 3);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const detail::Triangle t(mesh, f);
        if (!t.degenerate()) {
            N.row(f) = t.cross.transpose() / t.double_area;
        }
    }
    return N;
}

Eigen::MatrixX3d vertex_normals(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "vertex_normals");
    Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(mesh.V.rows(), 3);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const detail::Triangle t(mesh, f);
        if (t.degenerate()) {
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            N.row(mesh.F(f, k)) += 0.5 * t.cross.transpose();  // A_f n_f
        }
    }
    for (Eigen::Index i = 0; i < N.rows(); ++i) {
        const double length = N.row(i).norm();
        // Below this the direction is rounding noise; report "no normal" rather than garbage.
        if (length > 1e-300) {
            N.row(i) /= length;
        } else {
            N.row(i).setZero();
        }
    }
    return N;
}

}  // namespace genflow
