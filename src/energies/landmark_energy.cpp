// SPDX-License-Identifier: MIT
#include "genflow/energies/landmark_energy.h"

#include <cmath>
#include <string>
#include <utility>

#include "genflow/exceptions.h"
#include "operators/triangle.h"

namespace genflow {

LandmarkEnergy::LandmarkEnergy(Eigen::Index vertex_count, std::vector<Eigen::Index> vertices,
                               Eigen::MatrixX3d points, double length, Eigen::VectorXd weights)
    : vertex_count_(vertex_count),
      vertices_(std::move(vertices)),
      points_(std::move(points)),
      weights_(std::move(weights)) {
    const auto count = static_cast<Eigen::Index>(vertices_.size());
    if (weights_.size() == 0) {
        weights_ = Eigen::VectorXd::Ones(count);
    }
    if (count == 0 || count != points_.rows() || count != weights_.size()) {
        throw InvalidInput(
            "LandmarkEnergy: need one point and weight per landmark, and a landmark");
    }
    if (!detail::all_finite(weights_) || !(weights_.minCoeff() > 0)) {
        throw InvalidInput("LandmarkEnergy: weights must be positive and finite");
    }
    for (const Eigen::Index v : vertices_) {
        if (v < 0 || v >= vertex_count_) {
            throw InvalidInput("LandmarkEnergy: vertex " + std::to_string(v) + " outside 0.." +
                               std::to_string(vertex_count_ - 1));
        }
    }
    if (!detail::all_finite(points_) || !std::isfinite(length) || !(length > 0)) {
        throw InvalidInput("LandmarkEnergy: points must be finite and the length positive");
    }
    normalization_ = 1 / (weights_.sum() * length * length);
}

void LandmarkEnergy::check(const TriangleMesh& mesh) const {
    if (mesh.V.rows() != vertex_count_) {
        throw InvalidInput("LandmarkEnergy: the mesh has " + std::to_string(mesh.V.rows()) +
                           " vertices, the landmarks' " + std::to_string(vertex_count_));
    }
}

double LandmarkEnergy::value(const TriangleMesh& mesh) const {
    check(mesh);
    double sum = 0;
    for (std::size_t k = 0; k < vertices_.size(); ++k) {
        const auto row = static_cast<Eigen::Index>(k);
        sum += weights_[row] * (mesh.V.row(vertices_[k]) - points_.row(row)).squaredNorm();
    }
    return normalization_ * sum;
}

VertexField LandmarkEnergy::differential(const TriangleMesh& mesh) const {
    check(mesh);
    VertexField differential = VertexField::Zero(mesh.V.rows(), 3);
    for (std::size_t k = 0; k < vertices_.size(); ++k) {
        const auto row = static_cast<Eigen::Index>(k);
        differential.row(vertices_[k]) +=
            2 * normalization_ * weights_[row] * (mesh.V.row(vertices_[k]) - points_.row(row));
    }
    return differential;
}

std::optional<Linearization> LandmarkEnergy::linearize(const TriangleMesh& mesh) const {
    check(mesh);
    Linearization linear{Eigen::SparseMatrix<double>(vertex_count_, vertex_count_),
                         VertexField::Zero(vertex_count_, 3)};
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(vertices_.size());
    for (std::size_t k = 0; k < vertices_.size(); ++k) {
        const auto row = static_cast<Eigen::Index>(k);
        triplets.emplace_back(vertices_[k], vertices_[k], 2 * normalization_ * weights_[row]);
        linear.B.row(vertices_[k]) -= 2 * normalization_ * weights_[row] * points_.row(row);
    }
    linear.A.setFromTriplets(triplets.begin(), triplets.end());  // duplicates are summed
    return linear;
}

}  // namespace genflow
