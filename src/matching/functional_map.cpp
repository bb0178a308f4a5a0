// SPDX-License-Identifier: MIT
#include "matching/functional_map.h"

#include <Eigen/SVD>
#include <algorithm>

namespace genflow::detail {

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
