// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <vector>

#include "genflow/energies/energy.h"

namespace genflow {

/// Landmarks as soft constraints: vertex v_k drawn to the point y_k,
///
///     E(X) = 1/(W ℓ²) · Σ_k w_k |x_{v_k} − y_k|²,    k = 1..K,  W = Σ_k w_k,
///
/// the landmarks' weighted mean squared distance in units of the length ℓ (dimensionless, as
/// EdgeLengthEnergy, so that a weight times a length puts it beside d_H). Not in the paper:
/// shape matching adds it where the user clicked a few corresponding points
/// (MatchOptions::landmarks), which d_H, blind to which part lies where, cannot know.
///
/// - differential: ∂E/∂x_v = 2/(W ℓ²) · Σ_{k: v_k = v} w_k (x_v − y_k);
/// - linearization: exact (E is quadratic), A = 2/(W ℓ²) · diag(Σ_{k: v_k = v} w_k),
///   B = −2/(W ℓ²) · Σ_{k: v_k = v} w_k y_k.
class LandmarkEnergy final : public Energy {
public:
    /// `vertices[k]` of a mesh of `vertex_count` vertices is drawn to `points.row(k)` with the
    /// weight `weights[k]` (empty: 1 each); several landmarks may name one vertex.
    /// \throws InvalidInput if the sizes differ, there is no landmark, a vertex is outside
    ///         [0, vertex_count), a point is not finite, a weight not positive and finite or
    ///         `length` is not positive and finite.
    LandmarkEnergy(Eigen::Index vertex_count, std::vector<Eigen::Index> vertices,
                   Eigen::MatrixX3d points, double length, Eigen::VectorXd weights = {});

    /// \throws InvalidInput (value, differential, linearize) if `mesh` has another vertex count.
    [[nodiscard]] double value(const TriangleMesh& mesh) const override;
    [[nodiscard]] VertexField differential(const TriangleMesh& mesh) const override;
    [[nodiscard]] std::optional<Linearization> linearize(const TriangleMesh& mesh) const override;

private:
    void check(const TriangleMesh& mesh) const;

    Eigen::Index vertex_count_ = 0;
    std::vector<Eigen::Index> vertices_;
    Eigen::MatrixX3d points_;
    Eigen::VectorXd weights_;
    double normalization_ = 0;  // 1 / (W ℓ²)
};

}  // namespace genflow
