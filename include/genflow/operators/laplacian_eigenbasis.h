// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

#include "genflow/mesh.h"

namespace genflow {

/// All eigenpairs of the Laplace–Beltrami operator of a mesh, K φ = λ M φ (cotan stiffness,
/// barycentric lumped mass), in ascending order of λ.
struct LaplacianEigenbasis {
    /// λ_0 = 0 ≤ λ_1 ≤ …, one per vertex with mass; units of 1/length².
    Eigen::VectorXd values;
    /// #V × #values, column k is φ_k. The columns are M-orthonormal (φ_kᵀ M φ_l = δ_kl); the
    /// rows of vertices without mass (unreferenced, or only in degenerate faces) are 0.
    Eigen::MatrixXd functions;
    /// The lumped masses m_i (barycentric) of M, whose sum is the surface area.
    Eigen::VectorXd masses;
};

/// The eigenbasis of `mesh`'s Laplace–Beltrami operator (the basis of heat_kernel_signature()
/// and of functional maps). Solved densely, O(#V³): meant for coarse meshes. Vertices of zero
/// mass are left out of the eigenproblem.
/// \throws InvalidInput if the mesh is invalid (bad indices, non-finite coordinates), has zero
///         area or more than 4000 vertices.
[[nodiscard]] LaplacianEigenbasis laplacian_eigenbasis(const TriangleMesh& mesh);

}  // namespace genflow
