// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <vector>

namespace genflow {

/// The rows f of F for which `keep(f)` is true, in their order: a mesh made of part of another's
/// faces over the same vertices, so that a vertex index means the same in both.
template <typename Keep>
[[nodiscard]] Eigen::MatrixX3i faces_where(const Eigen::MatrixX3i& F, Keep keep) {
    Eigen::MatrixX3i kept(F.rows(), 3);
    Eigen::Index count = 0;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        if (keep(f)) {
            kept.row(count++) = F.row(f);
        }
    }
    kept.conservativeResize(count, 3);
    return kept;
}

/// One flag per vertex (size `num_vertices`): true for the vertices some face of F uses.
/// Indices must lie in [0, num_vertices).
[[nodiscard]] std::vector<bool> vertices_on_faces(const Eigen::MatrixX3i& F,
                                                  Eigen::Index num_vertices);

/// The vertices some face of F uses, in increasing order: the rows of vertices_on_faces() that
/// are true.
[[nodiscard]] std::vector<Eigen::Index> vertices_used_by(const Eigen::MatrixX3i& F,
                                                         Eigen::Index num_vertices);

}  // namespace genflow
