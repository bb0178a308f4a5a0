// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/SparseCore>

#include "genflow/mesh.h"

namespace genflow {

/// Options of `cotan_stiffness()`.
struct CotanOptions {
    /// Bound on |cot| of any angle. A face whose largest |cot| exceeds it has all three of its
    /// cotangents scaled down by the same factor, which keeps K positive semi-definite (clamping
    /// each one alone would not, for caps). The default only touches needles and caps (angles
    /// below about 0.06° or above 179.94°), whose exact stiffness would make the matrices of
    /// the flows needlessly ill-conditioned; well-shaped meshes are assembled exactly.
    double max_cotangent = 1e3;
};

/// The cotangent stiffness matrix K (paper §2, docs/formulas.md §1), #V×#V, sparse:
///
///     K_ij = −½ (cot α_ij + cot β_ij)   for an edge ij (one term on a boundary edge),
///     K_ii = −Σ_{j≠i} K_ij,
///
/// with α_ij, β_ij the angles opposite the edge.
///
/// **Sign convention:** K is symmetric *positive* semi-definite and K·1 = 0; it is the FEM
/// stiffness matrix ∫∇φ_i·∇φ_j. In the paper's notation K = −C, where C is the (negative
/// semi-definite) cotan Laplacian, so the Laplace–Beltrami operator is Δ = −M⁻¹K, the area
/// gradient is ∂A/∂X = K X, and the H1 metric is G = M + λK.
///
/// \note Works on any triangle mesh: boundaries, several components, non-manifold edges.
///       Zero-area faces contribute explicit zeros (the sparsity pattern depends only on F, so
///       factorizations can be reused); cotangents are bounded (see CotanOptions), so the result
///       is always finite and PSD.
/// \throws InvalidInput if F indexes outside V or V holds a non-finite coordinate.
[[nodiscard]] Eigen::SparseMatrix<double> cotan_stiffness(const TriangleMesh& mesh,
                                                          const CotanOptions& options = {});

}  // namespace genflow
