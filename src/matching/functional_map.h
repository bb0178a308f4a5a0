// SPDX-License-Identifier: MIT
// Functional maps between two shapes' Laplacian eigenbases (Ovsjanikov et al. 2012) and their
// refinement by ZoomOut (Melzi et al. 2019): the steps SpectralDescriptors and FineSpectrum
// share.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "matching/nearest_rows.h"

namespace genflow::detail {

/// The functional map C (size × size) fitted to a correspondence π (row of `from_functions` ->
/// row of `to_functions`) in the M-weighted least-squares sense: ψ(π(i)) ≈ φ(i) C, which is
/// C = φᵀ M ψ(π) as φ is M-orthonormal.
[[nodiscard]] Eigen::MatrixXd fitted_functional_map(const Eigen::MatrixXd& from_functions,
                                                    const Eigen::VectorXd& from_masses,
                                                    const Eigen::MatrixXd& to_functions,
                                                    const std::vector<Eigen::Index>& correspondence,
                                                    Eigen::Index size);

/// The orthogonal map nearest to fitted_functional_map() (U Vᵀ of its SVD): a near-isometry
/// keeps the basis orthonormal, so its map is orthogonal.
[[nodiscard]] Eigen::MatrixXd fitted_orthogonal_map(const Eigen::MatrixXd& from_functions,
                                                    const Eigen::VectorXd& from_masses,
                                                    const Eigen::MatrixXd& to_functions,
                                                    const std::vector<Eigen::Index>& correspondence,
                                                    Eigen::Index size);

/// Per function, the weight 1/√λ_k of the embedding ZoomOut matches in (the low functions vary
/// smoothly over whole parts, the high ones are noisier), with λ floored at 1/1000 of the
/// largest (for meshes of several components, whose λ vanish).
[[nodiscard]] Eigen::RowVectorXd embedding_weights(const Eigen::VectorXd& values);

/// ZoomOut from `correspondence`: for sizes from `first` to `count` by `step` (and `count`
/// itself), C fitted to the correspondence and made orthogonal (a near-isometry keeps the basis
/// orthonormal), then the correspondence becomes that of nearest neighbours of φ C and ψ, both
/// times `weights` (per function).
[[nodiscard]] std::vector<Eigen::Index> zoom_out(const Eigen::MatrixXd& from_functions,
                                                 const Eigen::VectorXd& from_masses,
                                                 const Eigen::MatrixXd& to_functions,
                                                 const Eigen::RowVectorXd& weights,
                                                 std::vector<Eigen::Index> correspondence,
                                                 Eigen::Index first, Eigen::Index count,
                                                 Eigen::Index step = 1);

}  // namespace genflow::detail
