// SPDX-License-Identifier: MIT
// For each row of one matrix, the nearest row of another: the correspondences of ZoomOut and of
// the spectral maps, found in their embeddings (a few thousand rows of a few dozen columns).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace genflow::detail {

/// For each row a of `from`, the first row b of `to` with the smallest |b|² − 2 a·b, the
/// product a·b computed as the whole matrix product from·toᵀ computes it. The products are made
/// by blocks of rows near one another, and a block of `to` whose bounding box lies farther from
/// a block of `from` than a row already found is skipped: the same rows as the whole product's,
/// for a fraction of its arithmetic.
[[nodiscard]] std::vector<Eigen::Index> nearest_rows(const Eigen::MatrixXd& from,
                                                     const Eigen::MatrixXd& to);

}  // namespace genflow::detail
