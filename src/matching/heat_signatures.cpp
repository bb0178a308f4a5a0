// SPDX-License-Identifier: MIT
#include "matching/heat_signatures.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/operators/heat_kernel_signature.h"

namespace genflow::detail {

namespace {

// The log signatures of `coarse`'s vertices with a positive signature (zero-mass vertices
// have none), and which vertices those are.
struct LogSignature {
    Eigen::MatrixXd values;
    std::vector<Eigen::Index> vertex;
};

LogSignature log_signature(const TriangleMesh& coarse) {
    const Eigen::MatrixXd signature = heat_kernel_signature(coarse);
    LogSignature result;
    for (Eigen::Index i = 0; i < signature.rows(); ++i) {
        if ((signature.row(i).array() > 0).all()) {
            result.vertex.push_back(i);
        }
    }
    result.values = signature(result.vertex, Eigen::all).array().log();
    return result;
}

}  // namespace

HeatSignatures::HeatSignatures(const TriangleMesh& template_mesh, const TriangleMesh& target,
                               Eigen::Index vertices)
    : template_vertices_(template_mesh.V.rows()),
      template_points_(Eigen::MatrixX3d(0, 3)),
      target_points_(Eigen::MatrixX3d(0, 3)) {
    const CoarseMesh coarse_template = coarsen(template_mesh, vertices);
    LogSignature from = log_signature(coarse_template.mesh);
    for (const Eigen::Index k : from.vertex) {
        template_vertex_.push_back(coarse_template.fine_vertex[static_cast<std::size_t>(k)]);
    }
    template_log_signature_ = std::move(from.values);

    const CoarseMesh coarse_target = coarsen(target, vertices);
    LogSignature to = log_signature(coarse_target.mesh);
    if (template_vertex_.empty() || to.vertex.empty()) {
        throw InvalidInput("HeatSignatures: a mesh has no vertex with area");
    }
    template_points_ = PointIndex(template_mesh.V(template_vertex_, Eigen::all));
    target_log_signature_ = std::move(to.values);
    target_points_ = PointIndex(coarse_target.mesh.V(to.vertex, Eigen::all));
}

double HeatSignatures::discrepancy(const Eigen::MatrixX3d& deformed) const {
    if (deformed.rows() != template_vertices_) {
        throw InvalidInput("HeatSignatures: the deformed template has " +
                           std::to_string(deformed.rows()) + " vertices, not " +
                           std::to_string(template_vertices_));
    }
    std::vector<double> squared(template_vertex_.size());
    for (std::size_t k = 0; k < template_vertex_.size(); ++k) {
        const Eigen::Vector3d position = deformed.row(template_vertex_[k]).transpose();
        const auto nearest = target_points_.nearest(position).first;
        squared[k] = (template_log_signature_.row(static_cast<Eigen::Index>(k)) -
                      target_log_signature_.row(nearest))
                         .squaredNorm();
    }
    const auto middle = squared.begin() + static_cast<std::ptrdiff_t>(squared.size() / 2);
    std::nth_element(squared.begin(), middle, squared.end());
    return *middle;
}

PointDescriptors HeatSignatures::descriptors(const Eigen::MatrixX3d& template_points,
                                             const Eigen::MatrixX3d& target_points,
                                             double length) const {
    const Eigen::RowVectorXd mean = template_log_signature_.colwise().mean();
    const Eigen::RowVectorXd deviation =
        (template_log_signature_.rowwise() - mean).array().square().colwise().mean().sqrt();
    const auto times = static_cast<double>(template_log_signature_.cols());
    // A time at which every template point has the same signature carries no information.
    const Eigen::RowVectorXd scale =
        (deviation.array() > 0).select(length / std::sqrt(times) / deviation.array(), 0.0);
    const auto at = [&](const Eigen::MatrixX3d& points, const PointIndex& index,
                        const Eigen::MatrixXd& log_signature) {
        Eigen::MatrixXd result(points.rows(), log_signature.cols());
        for (Eigen::Index i = 0; i < points.rows(); ++i) {
            const auto nearest = index.nearest(points.row(i).transpose()).first;
            result.row(i) = (log_signature.row(nearest) - mean).cwiseProduct(scale);
        }
        return result;
    };
    return {at(template_points, template_points_, template_log_signature_),
            at(target_points, target_points_, target_log_signature_)};
}

}  // namespace genflow::detail
