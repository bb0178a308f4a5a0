// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

#include "genflow/operators/laplacian_eigenbasis.h"

namespace genflow {

/// The wave kernel signature (Aubry, Schlickewei & Cremers 2011), #V × `energies`: the
/// probability that a quantum particle of log-energy e_s is found at vertex i,
///
///     w_i(e_s) = A · Σ_k φ_k(i)² g_s(log λ_k) / Σ_k g_s(log λ_k),   g_s(x) = exp(−(x − e_s)²/2σ²),
///
/// over the non-zero eigenpairs of `basis` (K φ = λ M φ, φ M-orthonormal), with A the surface
/// area. The energies e_s are spaced evenly over [log λ_1 + 2σ, log λ_K − 2σ] with σ seven times
/// their spacing (the paper's choice: each band overlaps its neighbours, and none runs off the
/// ends of the spectrum). Unlike the heat kernel signature, which averages ever more of the
/// spectrum as its time grows, each band picks out a range of frequencies: the low ones tell
/// parts of a shape apart, the high ones finer features. Dimensionless, like
/// heat_kernel_signature(): invariant under rigid motions, uniform scaling and isometric
/// bending, with Σ_i m_i w_i(e) = A.
/// \throws InvalidInput if the basis has fewer than 3 non-zero eigenvalues, zero area, or
///         `energies` is below 1.
[[nodiscard]] Eigen::MatrixXd wave_kernel_signature(const LaplacianEigenbasis& basis,
                                                    Eigen::Index energies = 100);

}  // namespace genflow
