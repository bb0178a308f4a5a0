// SPDX-License-Identifier: MIT
// The entries of the cotan stiffness matrix, face by face, in the one order that both
// cotan_stiffness() and StiffnessPattern sum them in: the two must agree to the bit.
#pragma once

#include <Eigen/Core>
#include <utility>

#include "genflow/mesh.h"
#include "genflow/operators/cotan_stiffness.h"
#include "operators/triangle.h"

namespace genflow::detail {

/// Entries per face that for_each_cotan_entry() emits.
constexpr int kCotanEntriesPerFace = 12;

/// The edge (i, j) opposite corner k of face f: its corners k+1 and k+2, in that order (the
/// order of the entries below, and of StiffnessPattern's slots).
inline std::pair<int, int> opposite_edge(const Eigen::MatrixX3i& F, Eigen::Index f, int k) {
    return {F(f, (k + 1) % 3), F(f, (k + 2) % 3)};
}

/// Calls weight(i, j, w) for each corner k of each face of `mesh` in turn (faces in order, then
/// corners), (i, j) the edge (k+1, k+2) opposite it and w = ½ cot of the angle at k (bounded as
/// CotanOptions says). A degenerate face gives zeros. Expects a valid mesh.
template <typename Weight>
void for_each_cotan_weight(const TriangleMesh& mesh, const CotanOptions& options, Weight&& weight) {
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const Triangle t(mesh, f);
        const Eigen::Vector3d cots =
            t.degenerate() ? Eigen::Vector3d::Zero() : t.bounded_cots(options.max_cotangent);
        for (int k = 0; k < 3; ++k) {
            const auto [i, j] = opposite_edge(mesh.F, f, k);
            weight(i, j, 0.5 * cots[k]);
        }
    }
}

/// Calls entry(row, column, value) for the 12 entries of each face of `mesh` in turn (faces
/// in order): per corner, with for_each_cotan_weight()'s (i, j, w), −w at (i, j) and (j, i)
/// and +w at (i, i) and (j, j). The pattern depends on F alone. Expects a valid mesh.
template <typename Entry>
void for_each_cotan_entry(const TriangleMesh& mesh, const CotanOptions& options, Entry&& entry) {
    for_each_cotan_weight(mesh, options, [&](int i, int j, double w) {
        entry(i, j, -w);
        entry(j, i, -w);
        entry(i, i, w);
        entry(j, j, w);
    });
}

}  // namespace genflow::detail
