// SPDX-License-Identifier: MIT
// The operators a functional map must commute with (Nogneng & Ovsjanikov 2017; Ren et al.
// 2018), in a shape's reduced eigenbasis Φ (#V × k, M-orthonormal):
// - multiplication by a descriptor f: g ↦ f g, which a map that preserves f preserves;
// - the orientation operator of f: g ↦ ⟨n, ∇f × ∇g⟩, the derivative of g along ∇f turned a
//   quarter turn in the tangent plane. A map that preserves f and the surface's orientation
//   preserves it; a map that reverses the orientation (a left–right reflection, the trap of
//   every intrinsic descriptor on a symmetric shape) changes its sign.
// And the descriptors signed by the orientation that the same device gives: ⟨n, ∇f × ∇g⟩ for two
// descriptors f and g, a function that a reflection negates where f and g are left unchanged.
#pragma once

#include <Eigen/Core>

#include "genflow/mesh.h"

namespace genflow::detail {

/// Φᵀ M diag(f) Φ: multiplication by `f` (#V) seen in the basis `functions` (#V × k), with the
/// lumped masses `masses`. Symmetric.
[[nodiscard]] Eigen::MatrixXd multiplication_operator(const Eigen::MatrixXd& functions,
                                                      const Eigen::VectorXd& masses,
                                                      const Eigen::VectorXd& f);

/// The orientation operator of `f` (#V, piecewise linear on `mesh`) in the basis `functions`:
/// entry (i, j) = ∫ φ_i ⟨n, ∇f × ∇φ_j⟩ dA. On a face with counter-clockwise corners (a, b, c),
/// ⟨n, ∇f × ∇B_a⟩ = ∇f · (x_c − x_b)/(2A) for the hat function B_a, so no normal is needed: the
/// faces' own orientation gives the sign. φ_i is integrated as the mean of its corners.
/// Antisymmetrized (the continuous operator is antisymmetric on a closed surface, as the field
/// n × ∇f has no divergence; the barycentric quadrature is so only approximately).
[[nodiscard]] Eigen::MatrixXd orientation_operator(const TriangleMesh& mesh,
                                                   const Eigen::MatrixXd& functions,
                                                   const Eigen::VectorXd& f);

/// The signed descriptor ⟨n, ∇f × ∇g⟩ of two functions `f` and `g` (#V, piecewise linear on
/// `mesh`): per face the normal component of the cross product of their gradients, spread to
/// the vertices as the area-weighted mean of their faces. An orientation-preserving isometry
/// keeps it; a reflection negates it. Gradients of descriptors are noisy at the scale of a few
/// faces, so it is then smoothed by projection onto the basis `functions` (#V × k,
/// M-orthonormal for the lumped `masses`).
[[nodiscard]] Eigen::VectorXd signed_descriptor(const TriangleMesh& mesh,
                                                const Eigen::MatrixXd& functions,
                                                const Eigen::VectorXd& masses,
                                                const Eigen::VectorXd& f, const Eigen::VectorXd& g);

}  // namespace genflow::detail
