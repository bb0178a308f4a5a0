// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <vector>

#include "genflow/mesh.h"
#include "genflow/operators/laplacian_eigenbasis.h"

namespace genflow {

/// Diffusion times of heat_kernel_signature() as fractions of the surface area (t has units of
/// length²), from the scale of a few faces of a 1000-vertex mesh to that of a limb.
[[nodiscard]] std::vector<double> default_heat_kernel_times();

/// The heat kernel signature (Sun, Ovsjanikov & Guibas 2009), #V × #times: the heat that a unit
/// source at vertex i keeps there after time t, relative to the mean,
///
///     h_i(t) = A · Σ_k exp(−λ_k t) φ_k(i)² / Σ_k exp(−λ_k t),
///
/// with (λ_k, φ_k) all the eigenpairs of K φ = λ M φ (cotan stiffness, barycentric lumped mass,
/// φ M-orthonormal), A the surface area and t = relative_time × A. Dividing by the heat trace
/// and the area makes it dimensionless: it does not change under rigid motions or uniform
/// scaling, and Σ_i m_i h_i(t) = A. It depends only on the intrinsic geometry (bending without
/// stretching leaves it unchanged), and at small t it grows with the Gaussian curvature K
/// (h ≈ 1 + (K − K̄)·t/3 on a closed surface of mean curvature K̄; exactly 1 on a round sphere),
/// which makes it a pose-independent descriptor of where a vertex lies on a shape.
///
/// The eigenproblem is solved densely (laplacian_eigenbasis()), O(#V³): meant for coarse meshes
/// (match() uses about 1000 vertices). Vertices of zero mass (unreferenced, or only in
/// degenerate faces) are left out of the eigenproblem and get 0.
/// \throws InvalidInput if the mesh is invalid (bad indices, non-finite coordinates), has zero
///         area or more than 4000 vertices, or a time is not positive and finite.
[[nodiscard]] Eigen::MatrixXd heat_kernel_signature(
    const TriangleMesh& mesh,
    const std::vector<double>& relative_times = default_heat_kernel_times());

/// The same from an eigenbasis already computed (all its pairs are used).
/// \throws InvalidInput if the basis has zero area or a time is not positive and finite.
[[nodiscard]] Eigen::MatrixXd heat_kernel_signature(
    const LaplacianEigenbasis& basis,
    const std::vector<double>& relative_times = default_heat_kernel_times());

}  // namespace genflow
