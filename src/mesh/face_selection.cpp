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

}  // namespace genflow
