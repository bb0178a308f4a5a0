// SPDX-License-Identifier: MIT
#include "genflow/matching/landmarks.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace genflow {

namespace {

// The landmarks' extent along their second principal direction must exceed this fraction of
// the first for the rotation to be determined: a numerical rank, far below any clicked layout.
constexpr double kRankTolerance = 1e-6;

}  // namespace

double landmark_mean_squared_distance(const std::vector<Landmark>& landmarks,
                                      const Eigen::MatrixX3d& positions) {
    double sum = 0;
    for (const Landmark& landmark : landmarks) {
        sum += (positions.row(landmark.vertex).transpose() - landmark.target_point).squaredNorm();
    }
    return landmarks.empty() ? 0 : sum / static_cast<double>(landmarks.size());
}

std::optional<Similarity> landmark_similarity(const std::vector<Landmark>& landmarks,
                                              const Eigen::MatrixX3d& template_vertices) {
    const auto count = static_cast<Eigen::Index>(landmarks.size());
    if (count < 3) {
        return std::nullopt;
    }
    Eigen::Matrix3Xd from(3, count);
    Eigen::Matrix3Xd to(3, count);
    for (Eigen::Index k = 0; k < count; ++k) {
        const Landmark& landmark = landmarks[static_cast<std::size_t>(k)];
        from.col(k) = template_vertices.row(landmark.vertex).transpose();
        to.col(k) = landmark.target_point;
    }
    const Eigen::Matrix3Xd centred = from.colwise() - from.rowwise().mean();
    const Eigen::Vector3d extents = Eigen::JacobiSVD<Eigen::Matrix3Xd>(centred).singularValues();
    if (!(extents[1] > kRankTolerance * extents[0])) {
        return std::nullopt;
    }
    const Eigen::Matrix4d fit = Eigen::umeyama(from, to, true);
    Similarity similarity;
    similarity.scale = fit.topLeftCorner<3, 3>().col(0).norm();
    similarity.rotation = fit.topLeftCorner<3, 3>() / similarity.scale;
    similarity.translation = fit.topRightCorner<3, 1>();
    return similarity;
}

}  // namespace genflow
