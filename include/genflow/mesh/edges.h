// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

namespace genflow {

/// The undirected edges of the faces F, each once, as #E×2 rows (i, j) with i < j, sorted.
/// Indices are taken as they are (no range check); faces with a repeated index contribute
/// their non-degenerate edges only.
[[nodiscard]] Eigen::MatrixX2i unique_edges(const Eigen::MatrixX3i& F);

}  // namespace genflow
