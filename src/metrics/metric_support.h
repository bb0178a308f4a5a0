// SPDX-License-Identifier: MIT
// Private helpers shared by the metrics.
#pragma once

#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/mesh.h"
#include "genflow/operators/mass_matrix.h"

namespace genflow::detail {

/// The mass matrix of `type` with every diagonal entry floored at 1e-10 × the mean diagonal,
/// so that isolated or fully degenerate vertices keep G positive definite. Their differentials
/// vanish, so the floor changes no velocity of a vertex that has area.
Eigen::SparseMatrix<double> floored_mass_matrix(const TriangleMesh& mesh, MassType type);

/// The lumped masses of `type` (row sums for Full), floored as above.
Eigen::VectorXd floored_lumped_masses(const TriangleMesh& mesh, MassType type);

/// Throws InvalidInput naming `caller` unless the mask is empty or has one entry per vertex.
inline void require_mask_size(const std::vector<bool>& mask, Eigen::Index vertices,
                              const char* caller) {
    if (!mask.empty() && static_cast<Eigen::Index>(mask.size()) != vertices) {
        throw InvalidInput(std::string(caller) + ": fixed-vertex mask has " +
                           std::to_string(mask.size()) + " entries for " +
                           std::to_string(vertices) + " vertices");
    }
}

/// Fixed vertices (Metric::set_fixed_vertices()): the rows and columns of `S` for them become
/// those of the identity, keeping the sparsity pattern (so symbolic analyses stay valid).
void pin_fixed(Eigen::SparseMatrix<double>& S, const std::vector<bool>& fixed);

/// `field` with the rows of fixed vertices zeroed.
[[nodiscard]] VertexField zero_fixed_rows(VertexField field, const std::vector<bool>& fixed);

/// Copies the rows of fixed vertices from `input` into `result`: an operator applied as
/// `result` then acts as the identity on them.
void copy_fixed_rows(VertexField& result, const VertexField& input, const std::vector<bool>& fixed);

/// A #V×3 field as the 3n vector of the metrics that couple coordinates (vertex i in entries
/// 3i, 3i+1, 3i+2: docs/formulas.md §6 and §7), and back.
[[nodiscard]] Eigen::VectorXd interleave(const VertexField& field);
[[nodiscard]] VertexField deinterleave(const Eigen::VectorXd& vector);

/// Throws InvalidInput naming `caller` unless `field` has `rows` rows.
inline void require_rows(const VertexField& field, Eigen::Index rows, const char* caller) {
    if (field.rows() != rows) {
        throw InvalidInput(std::string(caller) + ": field has " + std::to_string(field.rows()) +
                           " rows, the mesh " + std::to_string(rows) +
                           " vertices (was update() called?)");
    }
}

}  // namespace genflow::detail
