// SPDX-License-Identifier: MIT
#include "matching/functional_map.h"

#include <Eigen/SVD>
#include <algorithm>
#include <limits>

namespace genflow::detail {

std::vector<Eigen::Index> nearest_rows(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to) {
    // |a − b|² = |b|² − 2 a·b + |a|², the last the same for every b, by tiles of rows and
    // columns: a tile's products stay in the cache while their minima are taken, and its
    // buffer is small enough to be reused from the heap (one distance matrix of a block of rows
    // cost as much in page faults as the products). The column tiles are multiples of every
    // SIMD width, so each product is computed as in one whole product.
    constexpr Eigen::Index kRowTile = 1024;
    constexpr Eigen::Index kColumnTile = 256;
    const Eigen::RowVectorXd to_squared = to.rowwise().squaredNorm().transpose();
    std::vector<Eigen::Index> nearest(static_cast<std::size_t>(from.rows()), 0);
    Eigen::MatrixXd products(std::min(kRowTile, from.rows()), std::min(kColumnTile, to.rows()));
    for (Eigen::Index begin = 0; begin < from.rows(); begin += kRowTile) {
        const Eigen::Index rows = std::min(kRowTile, from.rows() - begin);
        Eigen::VectorXd smallest =
            Eigen::VectorXd::Constant(rows, std::numeric_limits<double>::infinity());
        for (Eigen::Index first = 0; first < to.rows(); first += kColumnTile) {
            const Eigen::Index columns = std::min(kColumnTile, to.rows() - first);
            auto distance = products.topLeftCorner(rows, columns);
            distance.noalias() =
                -2 * from.middleRows(begin, rows) * to.middleRows(first, columns).transpose();
            // The minima of all rows at once, column by column: the matrix is stored by
            // columns, and a walk along a row would touch a new cache line at every entry. The
            // first smallest entry wins, as minCoeff()'s does.
            for (Eigen::Index j = 0; j < columns; ++j) {
                for (Eigen::Index i = 0; i < rows; ++i) {
                    const double d = distance(i, j) + to_squared(first + j);
                    if (d < smallest[i]) {
                        smallest[i] = d;
                        nearest[static_cast<std::size_t>(begin + i)] = first + j;
                    }
                }
            }
        }
    }
    return nearest;
}

Eigen::MatrixXd fitted_functional_map(const Eigen::MatrixXd& from_functions,
                                      const Eigen::VectorXd& from_masses,
                                      const Eigen::MatrixXd& to_functions,
                                      const std::vector<Eigen::Index>& correspondence,
                                      Eigen::Index size) {
    return from_functions.leftCols(size).transpose() * from_masses.asDiagonal() *
           to_functions(correspondence, Eigen::seqN(0, size));
}

Eigen::RowVectorXd embedding_weights(const Eigen::VectorXd& values) {
    return values.array().max(1e-3 * values.maxCoeff()).rsqrt().matrix().transpose();
}

Eigen::MatrixXd fitted_orthogonal_map(const Eigen::MatrixXd& from_functions,
                                      const Eigen::VectorXd& from_masses,
                                      const Eigen::MatrixXd& to_functions,
                                      const std::vector<Eigen::Index>& correspondence,
                                      Eigen::Index size) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(
        fitted_functional_map(from_functions, from_masses, to_functions, correspondence, size),
        Eigen::ComputeFullU | Eigen::ComputeFullV);
    return svd.matrixU() * svd.matrixV().transpose();
}

std::vector<Eigen::Index> zoom_out(const Eigen::MatrixXd& from_functions,
                                   const Eigen::VectorXd& from_masses,
                                   const Eigen::MatrixXd& to_functions,
                                   const Eigen::RowVectorXd& weights,
                                   std::vector<Eigen::Index> correspondence, Eigen::Index first,
                                   Eigen::Index count, Eigen::Index step) {
    for (Eigen::Index size = std::min(first, count);;
         size = std::min(size + std::max<Eigen::Index>(step, 1), count)) {
        const Eigen::MatrixXd orthogonal =
            fitted_orthogonal_map(from_functions, from_masses, to_functions, correspondence, size);
        const auto scaled = weights.head(size).asDiagonal();
        correspondence = nearest_rows(from_functions.leftCols(size) * orthogonal * scaled,
                                      to_functions.leftCols(size) * scaled);
        if (size == count) {
            return correspondence;
        }
    }
}

}  // namespace genflow::detail
