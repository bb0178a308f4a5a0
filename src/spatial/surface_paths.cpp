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

namespace {

// Dijkstra from every source at once: each vertex's path length to the nearest source and, if
// `nearest` is given, that source's position in `sources` (ties to the earlier; -1 unreached).
Eigen::VectorXd shortest_paths(const ChordGraph& graph, const std::vector<Eigen::Index>& sources,
                               std::vector<Eigen::Index>* nearest) {
    Eigen::VectorXd distance =
        Eigen::VectorXd::Constant(static_cast<Eigen::Index>(graph.size()), kUnreachable);
    if (nearest != nullptr) {
        nearest->assign(graph.size(), -1);
    }
    using Entry = std::pair<double, Eigen::Index>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    for (std::size_t s = 0; s < sources.size(); ++s) {
        if (distance(sources[s]) > 0) {
            distance(sources[s]) = 0;
            if (nearest != nullptr) {
                (*nearest)[static_cast<std::size_t>(sources[s])] = static_cast<Eigen::Index>(s);
            }
            queue.emplace(0.0, sources[s]);
        }
    }
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > distance(v)) {
            continue;
        }
        for (const Chord& chord : graph[static_cast<std::size_t>(v)]) {
            if (d + chord.length < distance(chord.vertex)) {
                distance(chord.vertex) = d + chord.length;
                if (nearest != nullptr) {
                    (*nearest)[static_cast<std::size_t>(chord.vertex)] =
                        (*nearest)[static_cast<std::size_t>(v)];
                }
                queue.emplace(d + chord.length, chord.vertex);
            }
        }
    }
    return distance;
}

}  // namespace

Eigen::VectorXd path_lengths_from(const ChordGraph& graph, Eigen::Index source) {
    return shortest_paths(graph, {source}, nullptr);
}

std::vector<double> path_lengths_to(const ChordGraph& graph, Eigen::Index source,
                                    const std::vector<Eigen::Index>& targets) {
    std::vector<double> distance(graph.size(), kUnreachable);
    std::vector<bool> settled(graph.size(), false);
    std::size_t open_targets = 0;
    std::vector<bool> is_target(graph.size(), false);
    for (const Eigen::Index t : targets) {
        if (!is_target[static_cast<std::size_t>(t)]) {
            is_target[static_cast<std::size_t>(t)] = true;
            ++open_targets;
        }
    }
    using Entry = std::pair<double, Eigen::Index>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    distance[static_cast<std::size_t>(source)] = 0;
    queue.emplace(0.0, source);
    while (!queue.empty() && open_targets > 0) {
        const auto [d, v] = queue.top();
        queue.pop();
        const auto u = static_cast<std::size_t>(v);
        if (settled[u]) {
            continue;
        }
        settled[u] = true;
        if (is_target[u]) {
            --open_targets;
        }
        for (const Chord& chord : graph[u]) {
            auto& next = distance[static_cast<std::size_t>(chord.vertex)];
            if (d + chord.length < next) {
                next = d + chord.length;
                queue.emplace(next, chord.vertex);
            }
        }
    }
    std::vector<double> lengths;
    lengths.reserve(targets.size());
    for (const Eigen::Index t : targets) {
        lengths.push_back(distance[static_cast<std::size_t>(t)]);
    }
    return lengths;
}

std::vector<Eigen::Index> nearest_sources(const ChordGraph& graph,
                                          const std::vector<Eigen::Index>& sources) {
    std::vector<Eigen::Index> nearest;
    (void)shortest_paths(graph, sources, &nearest);
    return nearest;
}

}  // namespace genflow::detail
