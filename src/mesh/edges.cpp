// SPDX-License-Identifier: MIT
#include "genflow/mesh/edges.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace genflow {

Eigen::MatrixX2i unique_edges(const Eigen::MatrixX3i& F) {
    std::vector<std::pair<int, int>> edges;
    edges.reserve(static_cast<std::size_t>(3 * F.rows()));
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            const int a = F(f, k);
            const int b = F(f, (k + 1) % 3);
            if (a != b) {
                edges.emplace_back(std::min(a, b), std::max(a, b));
            }
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    Eigen::MatrixX2i E(static_cast<Eigen::Index>(edges.size()), 2);
    for (std::size_t e = 0; e < edges.size(); ++e) {
        E(static_cast<Eigen::Index>(e), 0) = edges[e].first;
        E(static_cast<Eigen::Index>(e), 1) = edges[e].second;
    }
    return E;
}

}  // namespace genflow
