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
        [](const HalfEdge& e) { return e.key.second; });
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

// Each edge once, in (lo, hi) order, by sorting whole half-edges: for faces with any index, such
// as negative ones, which unique_edges() cannot bucket.
Eigen::MatrixX2i unique_edges_by_sorting(const Eigen::MatrixX3i& F) {
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

// Each edge once, in (lo, hi) order: the faces' edges bucketed by their lower vertex (a counting
// sort of bare indices, four bytes an entry), each bucket's few higher vertices sorted and
// deduplicated in place. The order of sorting whole half-edges, at a third of its time.
Eigen::MatrixX2i unique_edges(const Eigen::MatrixX3i& F) {
    if (F.size() > 0 && F.minCoeff() < 0) {
        return unique_edges_by_sorting(F);
    }
    const int vertices = F.size() > 0 ? F.maxCoeff() + 1 : 0;
    const auto n = static_cast<std::size_t>(vertices);
    std::vector<int> start(n + 1, 0);
    const auto for_each_edge = [&F](auto&& visit) {
        for (Eigen::Index f = 0; f < F.rows(); ++f) {
            for (int k = 0; k < 3; ++k) {
                const int a = F(f, k);
                const int b = F(f, (k + 1) % 3);
                if (a != b) {
                    visit(std::min(a, b), std::max(a, b));
                }
            }
        }
    };
    for_each_edge([&](int lo, int) { ++start[static_cast<std::size_t>(lo) + 1]; });
    for (std::size_t v = 0; v < n; ++v) {
        start[v + 1] += start[v];
    }
    std::vector<int> higher(static_cast<std::size_t>(start[n]));
    std::vector<int> next(start.begin(), start.end() - 1);
    for_each_edge([&](int lo, int hi) {
        higher[static_cast<std::size_t>(next[static_cast<std::size_t>(lo)]++)] = hi;
    });
    // Compacted in place: the k-th kept edge goes to slot k, never past the entry being read
    // (at most one write per entry read), so no entry is overwritten before it is read.
    std::size_t kept = 0;
    std::vector<int> lower(higher.size());
    for (std::size_t v = 0; v < n; ++v) {
        const auto begin = higher.begin() + start[v];
        const auto end = higher.begin() + start[v + 1];
        std::sort(begin, end);
        for (auto it = begin; it != end; ++it) {
            if (it == begin || *it != *(it - 1)) {
                higher[kept] = *it;
                lower[kept++] = static_cast<int>(v);
            }
        }
    }
    Eigen::MatrixX2i E(static_cast<Eigen::Index>(kept), 2);
    for (std::size_t e = 0; e < kept; ++e) {
        E(static_cast<Eigen::Index>(e), 0) = lower[e];
        E(static_cast<Eigen::Index>(e), 1) = higher[e];
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
