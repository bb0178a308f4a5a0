// SPDX-License-Identifier: MIT
#include "matching/functional_map.h"

#include <Eigen/SVD>
#include <algorithm>

namespace genflow::detail {

std::vector<Eigen::Index> nearest_rows(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to) {
    // |a − b|² = |b|² − 2 a·b + |a|², the last the same for every b. Blocks of rows keep the
    // distance matrix small on meshes of ten thousand vertices; it is allocated once (a fresh
    // one per block cost as much in page faults as the products).
    constexpr Eigen::Index kBlock = 1024;
    const Eigen::RowVectorXd to_squared = to.rowwise().squaredNorm().transpose();
    std::vector<Eigen::Index> nearest(static_cast<std::size_t>(from.rows()));
    Eigen::MatrixXd products(std::min(kBlock, from.rows()), to.rows());
    for (Eigen::Index begin = 0; begin < from.rows(); begin += kBlock) {
        const Eigen::Index rows = std::min(kBlock, from.rows() - begin);
        auto distance = products.topRows(rows);
        distance.noalias() = -2 * from.middleRows(begin, rows) * to.transpose();
        // The minima of all rows at once, column by column: the matrix is stored by columns,
        // and a walk along a row would touch a new cache line at every entry. The first
        // smallest entry wins, as minCoeff()'s does.
        Eigen::VectorXd smallest = distance.col(0).array() + to_squared(0);
        std::vector<Eigen::Index> column(static_cast<std::size_t>(rows), 0);
        for (Eigen::Index j = 1; j < distance.cols(); ++j) {
            for (Eigen::Index i = 0; i < rows; ++i) {
                const double d = distance(i, j) + to_squared(j);
                if (d < smallest[i]) {
                    smallest[i] = d;
                    column[static_cast<std::size_t>(i)] = j;
                }
            }
        }
        std::copy(column.begin(), column.end(), nearest.begin() + begin);
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
