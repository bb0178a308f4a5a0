// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <vector>

#include "genflow/mesh.h"
#include "genflow/operators/laplacian_eigenbasis.h"
#include "genflow/spatial/closest_point.h"

namespace genflow {

/// The functions a map's commutativity is measured with by default: they resolve regions of
/// about 1/40 of the surface (a hand, a foot, one side of a head), where a map either keeps
/// the intrinsic geometry or not; fewer judged the matcher's results worse (docs/matching.md,
/// "The signatures' reading").
inline constexpr Eigen::Index kCommutativityFunctions = 40;

/// How far a map π from one surface to another is from commuting with their Laplace–Beltrami
/// operators, a score of a correspondence that needs no ground truth (an isometry commutes
/// exactly; Ovsjanikov et al. 2012, §5). With φ and ψ the first `functions` non-constant
/// eigenfunctions of `from` and `to`, C = φᵀ M ψ∘π pulls ψ back through the map (ψ interpolated
/// at each point of `map`), and with Λ the eigenvalues times each surface's area (so that the
/// score does not depend on either's size):
///
///     ‖C Λ_to − Λ_from C‖²_F / ‖C Λ_to‖²_F.
///
/// 0 for an isometry, about 1 or more for a map that mixes regions at random (and 1 for one
/// that puts every point on the same place). A symmetry of the surfaces commutes too: it tells
/// a right map from a wrong one, not left from right.
/// \param from_basis `from`'s eigenbasis (laplacian_eigenbasis()), at least functions + 1 pairs
/// \param to the surface mapped to, whose faces `map` refers to
/// \param to_basis `to`'s eigenbasis, at least functions + 1 pairs
/// \param map per vertex of `from`, its point on `to` (closest_points() of a deformed template)
/// \throws InvalidInput if a basis has too few pairs or the sizes do not agree, or `map` has a
///         face outside `to`.
[[nodiscard]] double laplacian_commutativity(const LaplacianEigenbasis& from_basis,
                                             const TriangleMesh& to,
                                             const LaplacianEigenbasis& to_basis,
                                             const std::vector<SurfacePoint>& map,
                                             Eigen::Index functions = kCommutativityFunctions);

}  // namespace genflow
