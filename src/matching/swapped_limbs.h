// SPDX-License-Identifier: MIT
// Limbs a match put on their mirror images, and which ones.
//
// A template whose stride puts its left leg where the target has its right one is matched with
// the two exchanged: each lands on the nearest surface, and nothing the match compares tells,
// since the heat kernel signatures and the geodesic distances of a left limb and of a right one
// agree. What does tell is which way each extremity lies from the rest of the body: the
// turning function of a pair of extremities (intrinsic_shape.h) changes sign under a reflection,
// so where the match put a limb on its mirror image, the functions of every pair with its
// extremity disagree with the target's over most of the body, and exchanging the images of the
// pair of extremities that raises their agreement most exchanges the two limbs the match had
// swapped (docs/measurements.md, "Swapped limbs").
#pragma once

#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

#include "genflow/mesh.h"
#include "matching/intrinsic_shape.h"

namespace genflow::detail {

/// How well a correspondence (a vertex of `to` per vertex of `from`) agrees with the target
/// about which way each of the template's extremities lies: for every pair of `from`'s
/// extremities, the correlation (weighted by the masses) between its turning function and
/// that of the pair's `images` (vertices of `to`, one per extremity), pulled back by the
/// correspondence; the mean over the pairs. Near 1 when the map keeps every direction; a limb
/// put on its mirror image lowers the pairs with its extremity; 0 with fewer than two
/// extremities.
[[nodiscard]] double turning_agreement(const IntrinsicShape& from, const IntrinsicShape& to,
                                       const std::vector<Eigen::Index>& correspondence,
                                       const std::vector<Eigen::Index>& images);

/// Where a match put the template's extremities, and how well it agrees.
struct LimbPlacement {
    /// Per analysed template vertex, the analysed target vertex nearest where the match put it.
    std::vector<Eigen::Index> correspondence;
    /// Per extremity of the template (IntrinsicShape::extremities), its vertex of
    /// `correspondence`.
    std::vector<Eigen::Index> images;
    double agreement = 0;  ///< turning_agreement() of the two
};

/// The placement of `deformed` (the position of each of `from`'s analysed vertices, as matched
/// onto the target that `to` analyses).
/// \throws InvalidInput if `deformed` does not have a row per analysed vertex of `from`.
[[nodiscard]] LimbPlacement place_limbs(const IntrinsicShape& from, const IntrinsicShape& to,
                                        const Eigen::MatrixX3d& deformed);

/// Where a match put the template's extremities, from `deformed`: a row per vertex of the mesh
/// `shapes.first` analyses (a level of the pyramid, as matched).
[[nodiscard]] LimbPlacement limbs_placed(const AnalysedShapes& shapes,
                                         const Eigen::MatrixX3d& deformed);

/// Exchanged limbs found in a match.
struct SwappedLimbs {
    /// The template extremities (indices into IntrinsicShape::extremities) whose images were
    /// exchanged, in the order they were; empty if none was.
    std::vector<std::pair<std::size_t, std::size_t>> exchanged;
    /// Where each extremity belongs after the exchanges (vertices of the target's analysis).
    std::vector<Eigen::Index> images;
    double agreement_before = 0;  ///< the match's turning_agreement()
    double agreement_after = 0;   ///< and with its extremities' images exchanged (or not)
};

/// The pairs of limbs that a match has exchanged. Of the pairs of counterparts (extremities
/// whose average geodesic distances agree: a left and a right limb) that the match put at the
/// target's extremities, the images of the one whose exchange raises turning_agreement() most
/// are exchanged (the match's correspondence kept), as long as that raises it by more than
/// `margin`. None is exchanged if none does, or if the exchanges leave the agreement below
/// `least_agreement`: a map that agrees that poorly is wrong for another reason than two limbs
/// exchanged, and exchanging them does not make it right.
[[nodiscard]] SwappedLimbs find_swapped_limbs(const IntrinsicShape& from, const IntrinsicShape& to,
                                              const LimbPlacement& match, double margin,
                                              double least_agreement = 0);

/// Each vertex of `template_mesh` (the mesh `from` analyses, or another in its frame: a level
/// of its pyramid) where the landmark map of the extremities at their exchanged places puts
/// it; std::nullopt if `swapped` exchanged nothing, or if that map puts every vertex on one
/// point.
[[nodiscard]] std::optional<Eigen::MatrixX3d> exchanged_placement(const TriangleMesh& template_mesh,
                                                                  const IntrinsicShape& from,
                                                                  const IntrinsicShape& to,
                                                                  const SwappedLimbs& swapped);

/// How far (geodesically, in units of √area) a match ended from the exchanges of `swapped`:
/// the largest distance between where they put an exchanged extremity and where `match` did.
[[nodiscard]] double exchange_drift(const IntrinsicShape& to, const SwappedLimbs& swapped,
                                    const LimbPlacement& match);

}  // namespace genflow::detail
