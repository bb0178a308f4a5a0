// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <vector>

#include "genflow/mesh.h"

namespace genflow {

/// A coarse version of a mesh whose vertices are a subset of the fine ones (docs/formulas.md §9,
/// step 1).
struct CoarseMesh {
    TriangleMesh mesh;                      ///< the coarse mesh (compact vertex numbering)
    std::vector<Eigen::Index> fine_vertex;  ///< coarse vertex k is fine vertex fine_vertex[k]
};

/// Simplifies `mesh` to about `target_vertices` by quadric-error half-edge collapses
/// (meshoptimizer's meshopt_simplify: every collapse moves a vertex onto a neighbour, so the
/// kept vertices keep their positions and the coarse vertices are a subset of the fine ones).
/// Topology is preserved (collapses that would change it are refused), so the result may stop
/// above the target; boundaries are kept. Unreferenced fine vertices are dropped, and so are
/// both faces of a fin (two faces on the same three vertices), which meshoptimizer leaves on
/// rare occasions. The result can still have a few non-manifold edges where the input has thin
/// features (a few in 10⁴ edges at intermediate resolutions); every operator of
/// genflow accepts them. With target_vertices ≥ the vertex count, only the clean-up happens.
/// \throws InvalidInput if the mesh has no face, bad indices or non-finite coordinates, or
///         target_vertices < 4.
[[nodiscard]] CoarseMesh coarsen(const TriangleMesh& mesh, Eigen::Index target_vertices);

/// coarsen() to the share `share` of the mesh's vertices (rounded up, at least 4): another
/// sampling and connectivity of the same surface, as `genflow eval` makes a target of a ground
/// truth ("target_simplified").
/// \throws InvalidInput if `share` is not in (0, 1], or as coarsen().
[[nodiscard]] CoarseMesh coarsen_to_share(const TriangleMesh& mesh, double share);

/// Where each fine vertex sits relative to a coarse mesh: on coarse face `face` at barycentric
/// `barycentric`, plus the offset `offset` = p − Σ β_b x_b (docs/formulas.md §9, step 2).
struct Embedding {
    Eigen::VectorXi face;
    Eigen::MatrixX3d barycentric;
    Eigen::MatrixX3d offset;
};

/// Embeds every vertex of `fine` in its closest face of `coarse` (both at rest), preferring
/// faces that face the same way as the vertex (n_f·n_p > 0), so that a vertex of a thin part
/// is not attached to the other side.
/// \throws InvalidInput if a mesh has no face, bad indices or non-finite coordinates.
[[nodiscard]] Embedding embed(const TriangleMesh& fine, const TriangleMesh& coarse);

/// Embeds every vertex of `fine` in a face of its coarsened version (coarsen()): the closest of
/// the faces around the coarse vertices nearest along the fine surface to the vertex and to its
/// neighbours, and two coarse rings further, preferring faces that face the same way. Parts that
/// touch without joining (a hand resting on a thigh) are not embedded in each other, as the
/// closest face of all would have them: carried, they would drag each other apart. Fine
/// vertices without coarse faces near them (a component coarsening dropped) are embedded as by
/// embed(fine, coarse.mesh).
/// \throws InvalidInput if a mesh has no face, bad indices or non-finite coordinates, or if
///         coarse.fine_vertex does not name a fine vertex for each coarse vertex.
[[nodiscard]] Embedding embed(const TriangleMesh& fine, const CoarseMesh& coarse);

/// The fine mesh after its coarse version moved from `coarse_rest` to `coarse_deformed` (same
/// faces), by rotation-interpolated local offsets (docs/formulas.md §9, step 4): each coarse vertex
/// gets the rotation R_b = polar(Σ_{j∈N(b)} (x'_j − x'_b)(x_j − x_b)ᵀ + h² n'_b n_bᵀ) of its one
/// ring, and each fine vertex goes to p' = Σ β_b x'_b + polar(Σ β_b R_b)·o. Exact for rigid
/// motions; the offsets rotate with the surface, so details are not sheared by bends.
/// \throws InvalidInput if the sizes of the embedding, meshes and positions disagree.
[[nodiscard]] TriangleMesh transfer(const TriangleMesh& fine_rest, const TriangleMesh& coarse_rest,
                                    const Eigen::MatrixX3d& coarse_deformed,
                                    const Embedding& embedding);

}  // namespace genflow
