// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

namespace genflow {

/// One 3-vector per vertex, #V×3, laid out like TriangleMesh::V (positions, velocities,
/// differentials of energies).
using VertexField = Eigen::MatrixX3d;

/// A plain triangle mesh: nothing but positions and connectivity, as in libigl.
///
///  - `V` is #V×3: row i holds the position of vertex i.
///  - `F` is #F×3: row f holds the 0-based vertex indices of triangle f, counter-clockwise when
///    seen from outside, so that face normals (x_b − x_a)×(x_c − x_a) point outward.
///
/// The type enforces nothing; `validate()` reports what a given mesh violates, and every
/// public function states which of those violations it tolerates.
struct TriangleMesh {
    Eigen::MatrixX3d V;
    Eigen::MatrixX3i F;

    [[nodiscard]] Eigen::Index num_vertices() const { return V.rows(); }
    [[nodiscard]] Eigen::Index num_faces() const { return F.rows(); }
};

}  // namespace genflow
