// SPDX-License-Identifier: MIT
// A placement of the template on the target that owes nothing to where the two are in space,
// for pairs whose poses differ so much that the flow from every rigid start settles limbs on
// the wrong ones (a kneeling figure onto a standing one; docs/measurements.md).
// - Each shape's extremities (the tips of limbs, the head, a tail) are the vertices whose
//   average geodesic distance to the rest of the shape is the largest within a neighbourhood
//   (as the samples of Blended Intrinsic Maps, Kim et al. 2011).
// - They are matched by their geodesic distances, which bending keeps: the largest sets of
//   pairs whose mutual distances agree are the maximal cliques of an association graph
//   (Bron–Kerbosch), and the most consistent of the largest ones are the candidates.
// - A candidate's landmarks give a functional map (Ovsjanikov et al. 2012): fitted to Gaussians
//   of the geodesic distance to each landmark, with the Laplacians' commutativity as the
//   regularizer, and with it a target vertex for every template vertex.
// - A shape's intrinsic symmetry (left and right) leaves several candidates about equally
//   consistent, and geodesics cannot tell them apart; the mirrored maps turn the surface over
//   (a triangle's image faces into the target). The candidate whose map keeps the orientation
//   best is kept.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

#include "genflow/matching/rigid_alignment.h"
#include "genflow/mesh.h"
#include "matching/intrinsic_shape.h"

namespace genflow::detail {

struct IntrinsicStart {
    /// Each template vertex at the target vertex it corresponds to (#V×3).
    Eigen::MatrixX3d placement;
    /// A rigid start that agrees with `placement`: scaled by the square root of the shapes'
    /// area ratio (which bending keeps), turned and moved onto `placement` in the least-squares
    /// sense at that scale (Umeyama).
    Similarity similarity;
    /// The extremities matched.
    int landmarks = 0;
    /// How well the map keeps the surface's orientation: the sum over template triangles of
    /// the signed area of their images along the target's normals, over the sum of its
    /// magnitude; 1 when no image is turned over.
    double orientation = 0;
};

/// The intrinsic start of `template_mesh` on `target` (each coarsened to about 1000 vertices
/// first: the geodesic distances are computed between all pairs). std::nullopt when fewer than
/// three extremities match.
/// \throws InvalidInput if a mesh is invalid or has no area.
[[nodiscard]] std::optional<IntrinsicStart> intrinsic_start(const TriangleMesh& template_mesh,
                                                            const TriangleMesh& target);

/// Up to `count` intrinsic starts from different landmark sets, the preferred one first (that
/// of intrinsic_start()), then the others by how well their maps keep the orientation: where
/// a symmetry makes the preferred one wrong (the kneeling man matched front to back), one of
/// the next is often right. Sets whose map puts every vertex on one point are left out.
/// \throws InvalidInput if a mesh is invalid or has no area.
[[nodiscard]] std::vector<IntrinsicStart> intrinsic_starts(const TriangleMesh& template_mesh,
                                                           const TriangleMesh& target,
                                                           std::size_t count);

/// intrinsic_starts() from the shapes' analyses (analyse_intrinsic_shape() of the template and
/// of the target), which the caller may use for more.
[[nodiscard]] std::vector<IntrinsicStart> intrinsic_starts(const TriangleMesh& template_mesh,
                                                           const IntrinsicShape& from,
                                                           const IntrinsicShape& to,
                                                           std::size_t count);

/// `start` (of `template_mesh`) at another similarity scale: the same rotation, and the
/// translation that fits the placement best at that scale (as start_from_map() fits it at the
/// areas' scale).
void rescale(IntrinsicStart& start, const TriangleMesh& template_mesh, double scale);

/// The start that puts each vertex of `template_mesh` (the mesh `from` analyses) where `map`
/// (a vertex of `to` per vertex of `from`) puts its nearest analysed vertex, and the
/// similarity that agrees with it (`landmarks` and `orientation` left 0); std::nullopt if it
/// puts every vertex on one point.
[[nodiscard]] std::optional<IntrinsicStart> start_from_map(const TriangleMesh& template_mesh,
                                                           const IntrinsicShape& from,
                                                           const IntrinsicShape& to,
                                                           const std::vector<Eigen::Index>& map);

}  // namespace genflow::detail
