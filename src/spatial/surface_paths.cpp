// SPDX-License-Identifier: MIT
#include "spatial/surface_paths.h"

#include <functional>
#include <queue>
#include <utility>

#include "genflow/mesh/edges.h"

namespace genflow::detail {

ChordGraph chord_graph(const TriangleMesh& mesh, int rings) {
    const auto n = static_cast<std::size_t>(mesh.V.rows());
    const std::vector<std::vector<Eigen::Index>> ring = vertex_neighbours(mesh.F, mesh.V.rows());
    ChordGraph graph(n);
    std::vector<Eigen::Index> stamp(n, -1);
    for (std::size_t a = 0; a < n; ++a) {
        std::vector<Eigen::Index> frontier{static_cast<Eigen::Index>(a)};
        stamp[a] = static_cast<Eigen::Index>(a);
        for (int r = 0; r < rings; ++r) {
            std::vector<Eigen::Index> next;
            for (const Eigen::Index v : frontier) {
                for (const Eigen::Index w : ring[static_cast<std::size_t>(v)]) {
                    if (stamp[static_cast<std::size_t>(w)] != static_cast<Eigen::Index>(a)) {
                        stamp[static_cast<std::size_t>(w)] = static_cast<Eigen::Index>(a);
                        next.push_back(w);
                        graph[a].push_back(
                            {w, (mesh.V.row(static_cast<Eigen::Index>(a)) - mesh.V.row(w)).norm()});
                    }
                }
            }
            frontier = std::move(next);
        }
    }
    return graph;
}

Eigen::VectorXd path_lengths_from(const ChordGraph& graph, Eigen::Index source) {
    Eigen::VectorXd distance =
        Eigen::VectorXd::Constant(static_cast<Eigen::Index>(graph.size()), kUnreachable);
    using Entry = std::pair<double, Eigen::Index>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    distance(source) = 0;
    queue.emplace(0.0, source);
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > distance(v)) {
            continue;
        }
        for (const Chord& chord : graph[static_cast<std::size_t>(v)]) {
            if (d + chord.length < distance(chord.vertex)) {
                distance(chord.vertex) = d + chord.length;
                queue.emplace(d + chord.length, chord.vertex);
            }
        }
    }
    return distance;
}

std::vector<Eigen::Index> nearest_sources(const ChordGraph& graph,
                                          const std::vector<Eigen::Index>& sources) {
    std::vector<double> distance(graph.size(), kUnreachable);
    std::vector<Eigen::Index> nearest(graph.size(), -1);
    using Entry = std::pair<double, Eigen::Index>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    for (std::size_t s = 0; s < sources.size(); ++s) {
        const auto v = static_cast<std::size_t>(sources[s]);
        if (nearest[v] < 0) {
            distance[v] = 0;
            nearest[v] = static_cast<Eigen::Index>(s);
            queue.emplace(0.0, sources[s]);
        }
    }
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > distance[static_cast<std::size_t>(v)]) {
            continue;
        }
        for (const Chord& chord : graph[static_cast<std::size_t>(v)]) {
            const auto w = static_cast<std::size_t>(chord.vertex);
            if (d + chord.length < distance[w]) {
                distance[w] = d + chord.length;
                nearest[w] = nearest[static_cast<std::size_t>(v)];
                queue.emplace(d + chord.length, chord.vertex);
            }
        }
    }
    return nearest;
}

}  // namespace genflow::detail
