// SPDX-License-Identifier: MIT
#include "genflow/operators/mesh_size.h"

#include "genflow/mesh/edges.h"
#include "operators/triangle.h"

namespace genflow {

double bounding_box_diagonal(const TriangleMesh& mesh) {
    if (!detail::all_finite(mesh.V)) {
        throw InvalidInput("bounding_box_diagonal: vertex positions must be finite");
    }
    if (mesh.V.rows() == 0) {
        return 0;
    }
    return (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
}

double mean_edge_length(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "mean_edge_length");
    const Eigen::MatrixX2i E = unique_edges(mesh.F);
    if (E.rows() == 0) {
        return 0;
    }
    double total = 0;
    for (Eigen::Index e = 0; e < E.rows(); ++e) {
        total += (mesh.V.row(E(e, 0)) - mesh.V.row(E(e, 1))).norm();
    }
    return total / static_cast<double>(E.rows());
}

}  // namespace genflow
