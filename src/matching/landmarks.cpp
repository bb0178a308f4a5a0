// SPDX-License-Identifier: MIT
#include "genflow/matching/landmarks.h"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace genflow {

namespace {

// The landmarks' extent along their second principal direction must exceed this fraction of
// the first for the rotation to be determined: a numerical rank, far below any clicked layout.
constexpr double kRankTolerance = 1e-6;

// The similarity taking the columns of `from` nearest to those of `to` with the `weights`
// (summing to 1): Umeyama's closed form on weighted moments, the cross-covariance's SVD giving
// the rotation (a reflection turned back) and its singular values over the weighted variance
// the scale; nothing when the weighted points lie on a line.
std::optional<Similarity> weighted_similarity(const Eigen::Matrix3Xd& from,
                                              const Eigen::Matrix3Xd& to,
                                              const Eigen::RowVectorXd& weights) {
    const Eigen::Matrix3Xd from_centred = from.colwise() - from * weights.transpose();
    const Eigen::Matrix3Xd to_centred = to.colwise() - to * weights.transpose();
    const Eigen::Matrix3Xd weighted_from = from_centred.array().rowwise() * weights.array();
    const Eigen::Vector3d extents =
        Eigen::JacobiSVD<Eigen::Matrix3Xd>(from_centred.array().rowwise() * weights.array().sqrt())
            .singularValues();
    if (!(extents[1] > kRankTolerance * extents[0])) {
        return std::nullopt;
    }
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(to_centred * weighted_from.transpose(),
                                                Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Vector3d signs = Eigen::Vector3d::Ones();
    if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) {
        signs[2] = -1;
    }
    Similarity similarity;
    similarity.rotation = svd.matrixU() * signs.asDiagonal() * svd.matrixV().transpose();
    similarity.scale =
        svd.singularValues().dot(signs) / (weighted_from.array() * from_centred.array()).sum();
    similarity.translation = to * weights.transpose() -
                             similarity.scale * similarity.rotation * (from * weights.transpose());
    return similarity;
}

}  // namespace

double landmark_mean_squared_distance(const std::vector<Landmark>& landmarks,
                                      const Eigen::MatrixX3d& positions) {
    double sum = 0;
    double weights = 0;
    for (const Landmark& landmark : landmarks) {
        sum += landmark.weight *
               (positions.row(landmark.vertex).transpose() - landmark.target_point).squaredNorm();
        weights += landmark.weight;
    }
    return landmarks.empty() ? 0 : sum / weights;
}

std::optional<Similarity> landmark_similarity(const std::vector<Landmark>& landmarks,
                                              const Eigen::MatrixX3d& template_vertices) {
    const auto count = static_cast<Eigen::Index>(landmarks.size());
    if (count < 3) {
        return std::nullopt;
    }
    Eigen::Matrix3Xd from(3, count);
    Eigen::Matrix3Xd to(3, count);
    Eigen::RowVectorXd weights(count);
    for (Eigen::Index k = 0; k < count; ++k) {
        const Landmark& landmark = landmarks[static_cast<std::size_t>(k)];
        from.col(k) = template_vertices.row(landmark.vertex).transpose();
        to.col(k) = landmark.target_point;
        weights[k] = landmark.weight;
    }
    return weighted_similarity(from, to, weights / weights.sum());
}

}  // namespace genflow
