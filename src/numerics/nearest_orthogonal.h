// SPDX-License-Identifier: MIT
// The orthogonal 3×3 matrix nearest to a given one (its polar factor): the rotation of an
// orthogonal Procrustes fit, or of a local frame from a covariance.
#pragma once

#include <Eigen/Core>
#include <Eigen/SVD>

namespace genflow::detail {

/// U Vᵀ for A = U Σ Vᵀ, the orthogonal matrix nearest to A (Frobenius norm); with `proper`, the
/// nearest rotation (the last column of U turned when U Vᵀ would reflect). The identity when A
/// vanishes.
[[nodiscard]] inline Eigen::Matrix3d nearest_orthogonal(const Eigen::Matrix3d& A,
                                                        bool proper = true) {
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
    if (!(svd.singularValues()[0] > 0)) {
        return Eigen::Matrix3d::Identity();
    }
    Eigen::Matrix3d U = svd.matrixU();
    if (proper && (U * svd.matrixV().transpose()).determinant() < 0) {
        U.col(2) *= -1;
    }
    return U * svd.matrixV().transpose();
}

}  // namespace genflow::detail
