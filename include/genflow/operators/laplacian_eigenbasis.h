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

/// The `count` lowest eigenpairs only, for meshes of any size: Lanczos iterations (Spectra) on
/// (K − σM)⁻¹M with σ a little below 0, K − σM factored once (CHOLMOD, else Eigen's
/// SimplicialLDLT). `count` is capped at the number of vertices with mass; small meshes (where
/// Lanczos would need nearly all vectors anyway) are solved densely and truncated. The same
/// ordering, masses and M-orthonormal functions as the full basis; an eigenspace of several
/// functions (a sphere's harmonics) comes as some orthonormal basis of it.
/// \throws InvalidInput if the mesh is invalid or has zero area, or `count` is below 1.
/// \throws SolverError if the iterations do not converge.
[[nodiscard]] LaplacianEigenbasis laplacian_eigenbasis(const TriangleMesh& mesh,
                                                       Eigen::Index count);

}  // namespace genflow
