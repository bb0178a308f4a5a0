// SPDX-License-Identifier: MIT
#include "genflow/mesh/edges.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace genflow {

namespace {

// Every face's edges as (min, max) pairs, sorted, each as often as faces use it.
std::vector<std::pair<int, int>> sorted_face_edges(const Eigen::MatrixX3i& F) {
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
    return edges;
}

}  // namespace

Eigen::MatrixX2i boundary_edges(const Eigen::MatrixX3i& F) {
    const auto edges = sorted_face_edges(F);
    std::vector<std::pair<int, int>> once;
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) {
            ++j;
        }
        if (j - i == 1) {
            once.push_back(edges[i]);
        }
        i = j;
    }
    Eigen::MatrixX2i E(static_cast<Eigen::Index>(once.size()), 2);
    for (std::size_t e = 0; e < once.size(); ++e) {
        E(static_cast<Eigen::Index>(e), 0) = once[e].first;
        E(static_cast<Eigen::Index>(e), 1) = once[e].second;
    }
    return E;
}

std::vector<bool> boundary_vertices(const Eigen::MatrixX3i& F, Eigen::Index num_vertices) {
    const Eigen::MatrixX2i edges = boundary_edges(F);
    std::vector<bool> boundary(static_cast<std::size_t>(num_vertices), false);
    for (Eigen::Index e = 0; e < edges.rows(); ++e) {
        boundary[static_cast<std::size_t>(edges(e, 0))] = true;
        boundary[static_cast<std::size_t>(edges(e, 1))] = true;
    }
    return boundary;
}

Eigen::MatrixX2i unique_edges(const Eigen::MatrixX3i& F) {
    auto edges = sorted_face_edges(F);
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    Eigen::MatrixX2i E(static_cast<Eigen::Index>(edges.size()), 2);
    for (std::size_t e = 0; e < edges.size(); ++e) {
        E(static_cast<Eigen::Index>(e), 0) = edges[e].first;
        E(static_cast<Eigen::Index>(e), 1) = edges[e].second;
    }
    return E;
}

std::vector<std::vector<Eigen::Index>> vertex_neighbours(const Eigen::MatrixX3i& F,
                                                         Eigen::Index num_vertices) {
    std::vector<std::vector<Eigen::Index>> neighbours(static_cast<std::size_t>(num_vertices));
    const Eigen::MatrixX2i edges = unique_edges(F);
    for (Eigen::Index e = 0; e < edges.rows(); ++e) {
        neighbours[static_cast<std::size_t>(edges(e, 0))].push_back(edges(e, 1));
        neighbours[static_cast<std::size_t>(edges(e, 1))].push_back(edges(e, 0));
    }
    return neighbours;
}

}  // namespace genflow
