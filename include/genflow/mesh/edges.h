// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <vector>

namespace genflow {

/// The undirected edges of the faces F, each once, as #E×2 rows (i, j) with i < j, sorted.
/// Indices are taken as they are (no range check); faces with a repeated index contribute
/// their non-degenerate edges only.
[[nodiscard]] Eigen::MatrixX2i unique_edges(const Eigen::MatrixX3i& F);

/// The edges of F used by exactly one face, as rows (i, j) with i < j, sorted (as
/// unique_edges()); none for a closed mesh.
[[nodiscard]] Eigen::MatrixX2i boundary_edges(const Eigen::MatrixX3i& F);

/// The edges of boundary_edges(), each as its one face runs it (rows (from, to)), in the same
/// order: around a hole of an oriented surface they chain into loops.
[[nodiscard]] Eigen::MatrixX2i oriented_boundary_edges(const Eigen::MatrixX3i& F);

/// One flag per vertex (size `num_vertices`): true for the vertices of boundary edges, the
/// edges used by exactly one face. Indices must lie in [0, num_vertices).
[[nodiscard]] std::vector<bool> boundary_vertices(const Eigen::MatrixX3i& F,
                                                  Eigen::Index num_vertices);

/// Each vertex's neighbours along the edges of F (its one ring, in no particular order), for
/// `num_vertices` vertices. Indices must lie in [0, num_vertices).
[[nodiscard]] std::vector<std::vector<Eigen::Index>> vertex_neighbours(const Eigen::MatrixX3i& F,
                                                                       Eigen::Index num_vertices);

}  // namespace genflow
