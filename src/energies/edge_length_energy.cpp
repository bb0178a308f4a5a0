// SPDX-License-Identifier: MIT
#include "genflow/energies/edge_length_energy.h"

#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/mesh/edges.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

Eigen::RowVector3d edge_vector(const TriangleMesh& mesh, const Eigen::MatrixX2i& edges,
                               Eigen::Index e) {
    return mesh.V.row(edges(e, 0)) - mesh.V.row(edges(e, 1));
}

const TriangleMesh& validated(const TriangleMesh& rest) {
    detail::require_valid_mesh(rest, "EdgeLengthEnergy");
    return rest;
}

}  // namespace

EdgeLengthEnergy::EdgeLengthEnergy(const TriangleMesh& rest)
    : vertex_count_(rest.V.rows()), edges_(unique_edges(validated(rest).F)) {
    rest_lengths_.resize(edges_.rows());
    double sum_of_squares = 0;
    for (Eigen::Index e = 0; e < edges_.rows(); ++e) {
        rest_lengths_[e] = edge_vector(rest, edges_, e).norm();
        sum_of_squares += rest_lengths_[e] * rest_lengths_[e];
    }
    if (!(sum_of_squares > 0)) {
        throw InvalidInput("EdgeLengthEnergy: the rest mesh has no edge of positive length");
    }
    normalization_ = 1 / sum_of_squares;
}

void EdgeLengthEnergy::check(const TriangleMesh& mesh) const {
    if (mesh.V.rows() != vertex_count_) {
        throw InvalidInput("EdgeLengthEnergy: the mesh has " + std::to_string(mesh.V.rows()) +
                           " vertices, its rest mesh " + std::to_string(vertex_count_));
    }
}

double EdgeLengthEnergy::value(const TriangleMesh& mesh) const {
    check(mesh);
    double sum = 0;
    for (Eigen::Index e = 0; e < edges_.rows(); ++e) {
        const double stretch = edge_vector(mesh, edges_, e).norm() - rest_lengths_[e];
        sum += stretch * stretch;
    }
    return normalization_ * sum;
}

VertexField EdgeLengthEnergy::differential(const TriangleMesh& mesh) const {
    check(mesh);
    VertexField differential = VertexField::Zero(mesh.V.rows(), 3);
    for (Eigen::Index e = 0; e < edges_.rows(); ++e) {
        const Eigen::RowVector3d d = edge_vector(mesh, edges_, e);
        const double length = d.norm();
        if (length > 0) {
            const Eigen::RowVector3d force =
                (2 * normalization_ * (length - rest_lengths_[e]) / length) * d;
            differential.row(edges_(e, 0)) += force;
            differential.row(edges_(e, 1)) -= force;
        }
    }
    return differential;
}

std::optional<Linearization> EdgeLengthEnergy::linearize(const TriangleMesh& mesh) const {
    check(mesh);
    // dE/dX = 2/Σℓ² Σ_e (d_e − ℓ_e d̂_e) (±): the d_e part is linear in X (the graph
    // Laplacian), the ℓ_e d̂_e part is frozen at X_t.
    const double k = 2 * normalization_;
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<std::size_t>(4 * edges_.rows()));
    Linearization linearization;
    linearization.B = VertexField::Zero(mesh.V.rows(), 3);
    for (Eigen::Index e = 0; e < edges_.rows(); ++e) {
        const int i = edges_(e, 0);
        const int j = edges_(e, 1);
        triplets.emplace_back(i, i, k);
        triplets.emplace_back(j, j, k);
        triplets.emplace_back(i, j, -k);
        triplets.emplace_back(j, i, -k);
        const Eigen::RowVector3d d = edge_vector(mesh, edges_, e);
        const double length = d.norm();
        // At a zero-length edge d_e = 0 and the differential has no term there: B takes none.
        if (length > 0) {
            const Eigen::RowVector3d pull = (k * rest_lengths_[e] / length) * d;
            linearization.B.row(i) -= pull;
            linearization.B.row(j) += pull;
        }
    }
    linearization.A.resize(mesh.V.rows(), mesh.V.rows());
    linearization.A.setFromTriplets(triplets.begin(), triplets.end());
    return linearization;
}

}  // namespace genflow
