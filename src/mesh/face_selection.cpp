// SPDX-License-Identifier: MIT
#include "genflow/mesh/face_selection.h"

namespace genflow {

std::vector<bool> vertices_on_faces(const Eigen::MatrixX3i& F, Eigen::Index num_vertices) {
    std::vector<bool> used(static_cast<std::size_t>(num_vertices), false);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            used[static_cast<std::size_t>(F(f, c))] = true;
        }
    }
    return used;
}

std::vector<Eigen::Index> vertices_used_by(const Eigen::MatrixX3i& F, Eigen::Index num_vertices) {
    const std::vector<bool> used = vertices_on_faces(F, num_vertices);
    std::vector<Eigen::Index> rows;
    for (Eigen::Index i = 0; i < num_vertices; ++i) {
        if (used[static_cast<std::size_t>(i)]) {
            rows.push_back(i);
        }
    }
    return rows;
}

}  // namespace genflow
