// SPDX-License-Identifier: MIT
#include "genflow/mesh/edges.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "mesh/sort_by_vertex.h"

namespace genflow {

namespace {

// A face's edge run from `from` to `to`, and its key (min, max) shared by both its faces.
struct HalfEdge {
    std::pair<int, int> key;
    int from;
    int to;
};

// Every face's half-edges, sorted by key: the faces of one edge end up next to each other.
std::vector<HalfEdge> sorted_half_edges(const Eigen::MatrixX3i& F) {
    int vertices = 0;
    std::vector<HalfEdge> edges;
    edges.reserve(static_cast<std::size_t>(3 * F.rows()));
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            const int a = F(f, k);
            const int b = F(f, (k + 1) % 3);
            if (a != b) {
                edges.push_back({{std::min(a, b), std::max(a, b)}, a, b});
                vertices = std::max({vertices, a + 1, b + 1});
            }
        }
    }
    detail::sort_by_vertex(
        edges, static_cast<std::size_t>(vertices), [](const HalfEdge& e) { return e.key.first; },
        [](const HalfEdge& x, const HalfEdge& y) { return x.key < y.key; });
    return edges;
}

// The half-edges whose edge no other face uses, in key order.
std::vector<HalfEdge> lone_half_edges(const Eigen::MatrixX3i& F) {
    const std::vector<HalfEdge> edges = sorted_half_edges(F);
    std::vector<HalfEdge> once;
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j].key == edges[i].key) {
            ++j;
        }
        if (j - i == 1) {
            once.push_back(edges[i]);
        }
        i = j;
    }
    return once;
}

}  // namespace

Eigen::MatrixX2i boundary_edges(const Eigen::MatrixX3i& F) {
    const std::vector<HalfEdge> once = lone_half_edges(F);
    Eigen::MatrixX2i E(static_cast<Eigen::Index>(once.size()), 2);
    for (std::size_t e = 0; e < once.size(); ++e) {
        E(static_cast<Eigen::Index>(e), 0) = once[e].key.first;
        E(static_cast<Eigen::Index>(e), 1) = once[e].key.second;
    }
    return E;
}

Eigen::MatrixX2i oriented_boundary_edges(const Eigen::MatrixX3i& F) {
    const std::vector<HalfEdge> once = lone_half_edges(F);
    Eigen::MatrixX2i E(static_cast<Eigen::Index>(once.size()), 2);
    for (std::size_t e = 0; e < once.size(); ++e) {
        E(static_cast<Eigen::Index>(e), 0) = once[e].from;
        E(static_cast<Eigen::Index>(e), 1) = once[e].to;
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
    std::vector<HalfEdge> edges = sorted_half_edges(F);
    edges.erase(std::unique(edges.begin(), edges.end(),
                            [](const HalfEdge& x, const HalfEdge& y) { return x.key == y.key; }),
                edges.end());
    Eigen::MatrixX2i E(static_cast<Eigen::Index>(edges.size()), 2);
    for (std::size_t e = 0; e < edges.size(); ++e) {
        E(static_cast<Eigen::Index>(e), 0) = edges[e].key.first;
        E(static_cast<Eigen::Index>(e), 1) = edges[e].key.second;
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
