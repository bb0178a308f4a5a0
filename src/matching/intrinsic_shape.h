// SPDX-License-Identifier: MIT
// What the intrinsic start and the check for swapped limbs know of a shape, independent of
// where it is in space: its geodesic distances, its extremities (the tips of limbs, the head,
// a tail) and its lowest Laplacian eigenfunctions, all at about 1000 vertices and in units of
// √area, so that nothing depends on the shape's scale.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <utility>
#include <vector>

#include "genflow/matching/multiresolution.h"
#include "genflow/matching/template_cache.h"
#include "genflow/mesh.h"

namespace genflow::detail {

/// An extremity has the largest average geodesic distance within this radius (in units of
/// √area): 5–12 per shape (a human's head, hands and feet; a cat's paws, tail, ears and
/// muzzle); 0.1 found up to 46 (fingers).
inline constexpr double kExtremityRadius = 0.15;

struct IntrinsicShape {
    CoarseMesh coarse;         ///< the shape analysed, coarsened to about 1000 vertices
    Eigen::MatrixXd distance;  ///< geodesic, between all its vertices (symmetric)
    Eigen::VectorXd average;   ///< each vertex's mean geodesic distance to the others
    /// The vertices whose average is the largest within a neighbourhood (as the samples of
    /// Blended Intrinsic Maps, Kim et al. 2011), the farthest on average first.
    std::vector<Eigen::Index> extremities;
    Eigen::MatrixXd functions;  ///< the lowest eigenfunctions, M-orthonormal at unit area
    Eigen::VectorXd masses;     ///< lumped, summing to 1
    Eigen::VectorXd values;     ///< the eigenvalues at unit area
    double unit = 1;            ///< √area
};

/// The analysis of `mesh`.
/// \throws InvalidInput if the mesh is invalid or has no area.
[[nodiscard]] IntrinsicShape analyse_intrinsic_shape(const TriangleMesh& mesh);

/// A template and a target analysed alike (analyse_intrinsic_shape()).
using AnalysedShapes = std::pair<IntrinsicShape, IntrinsicShape>;

/// analyse_intrinsic_shape() of a template's level, kept in `template_cache` where there is one,
/// and of the target's, side by side.
[[nodiscard]] AnalysedShapes analysed_shapes(const std::shared_ptr<TemplateCache>& template_cache,
                                             const TriangleMesh& template_level,
                                             const TriangleMesh& target_level);

/// Per vertex of the analysed shape, for each pair (a, b) of `sources` (its vertices), in the
/// order (0, 1), (0, 2), …, (1, 2), …: n · (∇d_a × ∇d_b), the sine of the angle from the way
/// to a to the way to b, d the geodesic distance (piecewise linear, the gradients per face,
/// averaged over the faces about a vertex by area). A reflection changes its sign, so these
/// functions tell left from right where geodesic distances cannot.
[[nodiscard]] Eigen::MatrixXd turning_functions(const IntrinsicShape& shape,
                                                const std::vector<Eigen::Index>& sources);

/// The target vertex of every analysed template vertex by the functional map fitted to
/// landmarks, `from_sources[k]` of `from` corresponding to `to_sources[k]` of `to` (analysed
/// vertices): the Gaussians of the geodesic distance to each landmark and the turning functions
/// of each pair of landmarks are to correspond, and the map to commute with the Laplacians.
[[nodiscard]] std::vector<Eigen::Index> landmark_map(const IntrinsicShape& from,
                                                     const IntrinsicShape& to,
                                                     const std::vector<Eigen::Index>& from_sources,
                                                     const std::vector<Eigen::Index>& to_sources);

}  // namespace genflow::detail
