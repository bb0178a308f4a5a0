// SPDX-License-Identifier: MIT
#include "matching/signature_discrepancy.h"

#include <algorithm>
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

SignatureDiscrepancy::SignatureDiscrepancy(const TriangleMesh& template_mesh,
                                           const TriangleMesh& target, Eigen::Index vertices)
    : template_vertices_(template_mesh.V.rows()), target_points_(Eigen::MatrixX3d(0, 3)) {
    const CoarseMesh coarse_template = coarsen(template_mesh, vertices);
    LogSignature from = log_signature(coarse_template.mesh);
    for (const Eigen::Index k : from.vertex) {
        template_vertex_.push_back(coarse_template.fine_vertex[static_cast<std::size_t>(k)]);
    }
    template_log_signature_ = std::move(from.values);

    const CoarseMesh coarse_target = coarsen(target, vertices);
    LogSignature to = log_signature(coarse_target.mesh);
    if (template_vertex_.empty() || to.vertex.empty()) {
        throw InvalidInput("SignatureDiscrepancy: a mesh has no vertex with area");
    }
    target_log_signature_ = std::move(to.values);
    target_points_ = PointIndex(coarse_target.mesh.V(to.vertex, Eigen::all));
}

double SignatureDiscrepancy::operator()(const Eigen::MatrixX3d& deformed) const {
    if (deformed.rows() != template_vertices_) {
        throw InvalidInput("SignatureDiscrepancy: the deformed template has " +
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

}  // namespace genflow::detail
