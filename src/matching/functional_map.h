// SPDX-License-Identifier: MIT
// Functional maps between two shapes' Laplacian eigenbases (Ovsjanikov et al. 2012) and their
// refinement by ZoomOut (Melzi et al. 2019): the steps SpectralDescriptors, find_turned_parts()
// and fitted_to_map() share.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "genflow/mesh.h"

namespace genflow::detail {

/// For each row of `from`, the nearest row of `to` (brute force, by blocks of matrix products:
/// a few thousand rows of a few dozen columns).
[[nodiscard]] std::vector<Eigen::Index> nearest_rows(const Eigen::MatrixXd& from,
                                                     const Eigen::MatrixXd& to);

/// The functional map C (size × size) fitted to a correspondence π (row of `from_functions` ->
/// row of `to_functions`) in the M-weighted least-squares sense: ψ(π(i)) ≈ φ(i) C, which is
/// C = φᵀ M ψ(π) as φ is M-orthonormal.
[[nodiscard]] Eigen::MatrixXd fitted_functional_map(const Eigen::MatrixXd& from_functions,
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

/// Where a fine functional map between a template and a target puts each template vertex.
struct VertexMap {
    std::vector<Eigen::Index> target_vertex;  ///< per template vertex
    Eigen::VectorXd template_masses;          ///< lumped (barycentric), as the eigenbasis's
    Eigen::Index functions = 0;               ///< eigenfunctions of the map (0: none was found)

    /// The smallest part's area the map tells apart: 1/functions of the template's (60
    /// functions tell about 60 regions apart). Needs functions > 0.
    [[nodiscard]] double resolved_area() const {
        return template_masses.sum() / static_cast<double>(functions);
    }
};

/// The map of `functions` non-constant eigenfunctions that a match implies: ZoomOut from 10 by 5
/// in the embedding of ψ_k/√λ_k, from the match's own correspondence (each template vertex with
/// the target vertex nearest to where `deformed` puts it). `template_rest` gives the template's
/// connectivity and intrinsic geometry. Lanczos eigenbases (any size), brute-force nearest
/// neighbours: meant for meshes of a few thousand vertices (at 50 000 the neighbours take
/// minutes).
/// \throws InvalidInput if `deformed` does not have the template's vertex count.
[[nodiscard]] VertexMap zoomed_out_map(const TriangleMesh& template_rest,
                                       const Eigen::MatrixX3d& deformed, const TriangleMesh& target,
                                       int functions = 60);

}  // namespace genflow::detail
