// SPDX-License-Identifier: MIT
// Shortest paths over a mesh's surface, on a graph of chords between vertices a few edges apart
// (or along the edges only).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "genflow/mesh.h"

namespace genflow::detail {

struct Chord {
    Eigen::Index vertex;
    double length;
};

/// Per vertex, its chords: to each vertex at most `rings` edges away, with the straight length.
using ChordGraph = std::vector<std::vector<Chord>>;

inline constexpr double kUnreachable = std::numeric_limits<double>::infinity();

/// The chord graph of `mesh` to `rings` edges (indices must be valid). With 2, paths over long
/// thin triangles do not zigzag as they do along the edges alone (on the demo's limb up to 3.8
/// times the straight distance between points 1.4 % of the diagonal apart); but on a coarse
/// mesh bent sharply (a knee) the chords cut across the bend, and the edges do not.
[[nodiscard]] ChordGraph chord_graph(const TriangleMesh& mesh, int rings);

/// The length of the shortest chord path from `source` to every vertex (Dijkstra);
/// kUnreachable on other components.
[[nodiscard]] Eigen::VectorXd path_lengths_from(const ChordGraph& graph, Eigen::Index source);

/// The length of the shortest chord path from `source` to each of `targets`, in their order
/// (Dijkstra, stopped once every target is settled: cheap when they are near the source);
/// kUnreachable for targets on other components. Indices must be valid.
[[nodiscard]] std::vector<double> path_lengths_to(const ChordGraph& graph, Eigen::Index source,
                                                  const std::vector<Eigen::Index>& targets);

/// Per vertex, the position in `sources` of the source nearest along the chord paths (one
/// Dijkstra from all of them at once; ties go to the earlier source), or -1 on components
/// without a source. Sources must be valid vertex indices.
[[nodiscard]] std::vector<Eigen::Index> nearest_sources(const ChordGraph& graph,
                                                        const std::vector<Eigen::Index>& sources);

}  // namespace genflow::detail
