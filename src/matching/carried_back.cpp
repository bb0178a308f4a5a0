// SPDX-License-Identifier: MIT
#include "matching/carried_back.h"

#include <optional>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "matching/counterparts.h"
#include "spatial/point_index.h"

namespace genflow::detail {

Eigen::MatrixX3d carried_back(const RepairedSurface& repaired, const Eigen::MatrixX3d& input_rest,
                              const Eigen::MatrixX3d& positions) {
    if (positions.rows() != repaired.mesh.V.rows()) {
        throw InvalidInput("carried_back: need " + std::to_string(repaired.mesh.V.rows()) +
                           " positions, got " + std::to_string(positions.rows()));
    }
    const auto input_vertices = static_cast<Eigen::Index>(repaired.repaired_vertex.size());
    std::vector<Eigen::Index> carried;
    for (Eigen::Index v = 0; v < input_vertices; ++v) {
        if (repaired.repaired_vertex[static_cast<std::size_t>(v)] >= 0) {
            carried.push_back(v);
        }
    }
    // The nearest carried vertex is searched for only where some vertex is not carried (most
    // repairs only remove faces or weld vertices).
    std::optional<PointIndex> index;
    if (static_cast<Eigen::Index>(carried.size()) < input_vertices) {
        index.emplace(input_rest(carried, Eigen::all));
    }
    Eigen::MatrixX3d moved(input_vertices, 3);
    for (Eigen::Index v = 0; v < input_vertices; ++v) {
        const Eigen::Index own = repaired.repaired_vertex[static_cast<std::size_t>(v)];
        if (own >= 0) {
            moved.row(v) = positions.row(own);
            continue;
        }
        const Eigen::Index nearest =
            carried[static_cast<std::size_t>(index->nearest(input_rest.row(v).transpose()).first)];
        const Eigen::Index by = repaired.repaired_vertex[static_cast<std::size_t>(nearest)];
        moved.row(v) = input_rest.row(v) + positions.row(by) - input_rest.row(nearest);
    }
    return moved;
}

Eigen::MatrixX3d carried_counterparts(const RepairedSurface& repaired,
                                      const Eigen::MatrixX3d& counterparts,
                                      const Eigen::MatrixX3d& deformed,
                                      const TriangleMesh& target) {
    const auto input_vertices = static_cast<Eigen::Index>(repaired.repaired_vertex.size());
    if (counterparts.rows() != repaired.mesh.V.rows() || deformed.rows() != input_vertices) {
        throw InvalidInput("carried_counterparts: need " + std::to_string(repaired.mesh.V.rows()) +
                           " counterparts and " + std::to_string(input_vertices) +
                           " deformed vertices, got " + std::to_string(counterparts.rows()) +
                           " and " + std::to_string(deformed.rows()));
    }
    // The closest points of every vertex, though only the vertices not carried need them: a
    // repair that leaves vertices out is rare, and the query is cheap beside a match.
    Eigen::MatrixX3d carried = closest_counterparts(deformed, target);
    for (Eigen::Index v = 0; v < input_vertices; ++v) {
        const Eigen::Index own = repaired.repaired_vertex[static_cast<std::size_t>(v)];
        if (own >= 0) {
            carried.row(v) = counterparts.row(own);
        }
    }
    return carried;
}

}  // namespace genflow::detail
