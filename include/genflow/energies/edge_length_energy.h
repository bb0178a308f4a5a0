// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

#include "genflow/energies/energy.h"

namespace genflow {

/// Stretching energy of the edges against their lengths in a rest mesh (a mass-spring
/// membrane):
///
///     E(X) = Σ_e (|x_i − x_j| − ℓ_e)² / Σ_e ℓ_e²,    e = (i, j), ℓ_e its length at rest.
///
/// Dimensionless (the relative mean-square stretch): zero exactly for the isometries of the
/// rest mesh's edge graph, which include rigid motions and bending at its edges, and (s − 1)²
/// for a uniform scaling by s. Not in the paper: shape matching adds it to d_H so that the
/// template's intrinsic geometry, which d_H cannot see, stays where a nearly isometric pose
/// change keeps it (MatchOptions::guided.stretch_weight).
///
/// - differential: ∂E/∂x_i = 2/Σℓ² · Σ_{e∋i} (|d_e| − ℓ_e) d_e/|d_e|, d_e = x_i − x_j (an edge of
///   zero length contributes nothing there, its subgradient).
/// - linearization: the local-global split of the springs, A = 2/Σℓ² · L (L the graph Laplacian
///   of the edges, symmetric PSD), B = −2/Σℓ² · Σ_e ℓ_e (±d̂_e) with the directions d̂_e frozen
///   at X_t; exact at X_t.
class EdgeLengthEnergy final : public Energy {
public:
    /// Rest lengths of the unique edges of `rest`'s faces.
    /// \throws InvalidInput if `rest` has bad indices, non-finite coordinates or no edge of
    ///         positive length.
    explicit EdgeLengthEnergy(const TriangleMesh& rest);

    /// \throws InvalidInput (value, differential, linearize) if `mesh` has another vertex count
    ///         than the rest mesh.
    [[nodiscard]] double value(const TriangleMesh& mesh) const override;
    [[nodiscard]] VertexField differential(const TriangleMesh& mesh) const override;
    [[nodiscard]] std::optional<Linearization> linearize(const TriangleMesh& mesh) const override;

    /// The edges (i, j), i < j, and their rest lengths.
    [[nodiscard]] const Eigen::MatrixX2i& edges() const { return edges_; }
    [[nodiscard]] const Eigen::VectorXd& rest_lengths() const { return rest_lengths_; }

private:
    void check(const TriangleMesh& mesh) const;

    Eigen::Index vertex_count_ = 0;
    Eigen::MatrixX2i edges_;
    Eigen::VectorXd rest_lengths_;
    double normalization_ = 0;  // 1 / Σ ℓ_e²
};

}  // namespace genflow
