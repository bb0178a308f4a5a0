// SPDX-License-Identifier: MIT
#include "genflow/operators/volume.h"

#include "operators/triangle.h"

namespace genflow {

double enclosed_volume(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "enclosed_volume");
    double six_volume = 0;
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const detail::Triangle t(mesh, f);
        six_volume += t.x[0].dot(t.x[1].cross(t.x[2]));
    }
    return six_volume / 6;
}

VertexField enclosed_volume_gradient(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "enclosed_volume_gradient");
    VertexField gradient = VertexField::Zero(mesh.V.rows(), 3);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const detail::Triangle t(mesh, f);
        for (int k = 0; k < 3; ++k) {
            gradient.row(mesh.F(f, k)) += t.x[(k + 1) % 3].cross(t.x[(k + 2) % 3]).transpose() / 6;
        }
    }
    return gradient;
}

}  // namespace genflow
