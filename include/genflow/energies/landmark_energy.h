// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <vector>

#include "genflow/energies/energy.h"

namespace genflow {

/// Landmarks as soft constraints: vertex v_k drawn to the point y_k,
///
///     E(X) = 1/(K ℓ²) · Σ_k |x_{v_k} − y_k|²,    k = 1..K,
///
/// the landmarks' mean squared distance in units of the length ℓ (dimensionless, as
/// EdgeLengthEnergy, so that a weight times a length puts it beside d_H). Not in the paper:
/// shape matching adds it where the user clicked a few corresponding points
/// (MatchOptions::landmarks), which d_H, blind to which part lies where, cannot know.
///
/// - differential: ∂E/∂x_v = 2/(K ℓ²) · Σ_{k: v_k = v} (x_v − y_k);
/// - linearization: exact (E is quadratic), A = 2/(K ℓ²) · diag(n_v) with n_v the landmarks on
///   vertex v, B = −2/(K ℓ²) · Σ_{k: v_k = v} y_k.
class LandmarkEnergy final : public Energy {
public:
    /// `vertices[k]` of a mesh of `vertex_count` vertices is drawn to `points.row(k)`; several
    /// landmarks may name one vertex.
    /// \throws InvalidInput if the sizes differ, there is no landmark, a vertex is outside
    ///         [0, vertex_count), a point is not finite or `length` is not positive and finite.
    LandmarkEnergy(Eigen::Index vertex_count, std::vector<Eigen::Index> vertices,
                   Eigen::MatrixX3d points, double length);

    /// \throws InvalidInput (value, differential, linearize) if `mesh` has another vertex count.
    [[nodiscard]] double value(const TriangleMesh& mesh) const override;
    [[nodiscard]] VertexField differential(const TriangleMesh& mesh) const override;
    [[nodiscard]] std::optional<Linearization> linearize(const TriangleMesh& mesh) const override;

private:
    void check(const TriangleMesh& mesh) const;

    Eigen::Index vertex_count_ = 0;
    std::vector<Eigen::Index> vertices_;
    Eigen::MatrixX3d points_;
    double normalization_ = 0;  // 1 / (K ℓ²)
};

}  // namespace genflow
