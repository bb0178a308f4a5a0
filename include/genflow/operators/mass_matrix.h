// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/SparseCore>

#include "genflow/mesh.h"

namespace genflow {

/// Which mass matrix (docs/formulas.md §1).
enum class MassType {
    /// The consistent FEM mass matrix: M_ij = Σ_{f∋i,j} A_f/12, M_ii = Σ_{f∋i} A_f/6.
    /// UᵀMW is the exact L2 product of the piecewise-linear fields U and W.
    Full,
    /// Lumped, diagonal: m_i = Σ_{f∋i} A_f/3 (the row sums of the full matrix).
    Barycentric,
    /// Lumped, diagonal, mixed Voronoi areas of Meyer et al. 2002: Voronoi cells on
    /// non-obtuse triangles, A_f/2 at an obtuse corner and A_f/4 at the other two.
    Voronoi
};

/// The mass matrix of `type`, #V×#V, sparse (diagonal for the lumped types). Its entries sum to
/// the surface area for every type.
///
/// \note Zero-area faces get zero mass, so a vertex whose faces are all degenerate (or that no
///       face references) has a zero row: callers that invert masses must guard against it.
/// \throws InvalidInput if F indexes outside V or V holds a non-finite coordinate.
[[nodiscard]] Eigen::SparseMatrix<double> mass_matrix(const TriangleMesh& mesh, MassType type);

/// The diagonal of the lumped mass matrix of `type` as a #V vector; for MassType::Full, the row
/// sums (equal to the barycentric masses).
/// \throws InvalidInput as `mass_matrix()`.
[[nodiscard]] Eigen::VectorXd lumped_masses(const TriangleMesh& mesh, MassType type);

}  // namespace genflow
