// SPDX-License-Identifier: MIT
// The intrinsic view of one level of a match, fine enough to see a thumb: the lowest eigenpairs
// of the level's template at rest and of its target (Lanczos, any size), computed once for the
// fine functional maps the level asks for: the one that turns back parts placed turned over
// (turned_parts.h) and guides the first fit (map_fit.h), and the one of each further fit.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "genflow/mesh.h"
#include "genflow/operators/laplacian_eigenbasis.h"
#include "spatial/point_index.h"

namespace genflow::detail {

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

/// The sizes ZoomOut starts from, each giving one map, in the order a fit to them is preferred
/// (first_kept_fit()). Its first map is the match's own correspondence seen through that many
/// functions: few let ZoomOut set whole limbs right, more keep the match's own left and right
/// where few functions cannot tell them (docs/measurements.md, "Fits to the fine map").
inline constexpr std::array<Eigen::Index, 2> kFineMapFirstSizes{10, 20};

class FineSpectrum {
public:
    /// The `functions` lowest non-constant eigenpairs of `template_rest` (the template's
    /// connectivity and intrinsic geometry) and of `target`.
    /// \throws InvalidInput if a mesh is invalid or has zero area.
    /// \throws SolverError if the Lanczos iterations do not converge.
    FineSpectrum(const TriangleMesh& template_rest, const TriangleMesh& target, int functions = 60);

    /// The map a match implies: ZoomOut from `first_size` by 5 functions in the embedding of
    /// ψ_k/√λ_k, from the match's own correspondence (each template vertex with the target
    /// vertex nearest to where `deformed` puts it). Brute-force nearest neighbours: meant for
    /// meshes of a few thousand vertices (at 50 000 they take minutes).
    /// \throws InvalidInput if `deformed` does not have the template's vertex count or
    ///         `first_size` is not positive.
    [[nodiscard]] VertexMap zoomed_out_map(const Eigen::MatrixX3d& deformed,
                                           Eigen::Index first_size = kFineMapFirstSizes[0]) const;

    /// The maps ZoomOut finds from each of kFineMapFirstSizes, in that order.
    [[nodiscard]] std::vector<VertexMap> zoomed_out_maps(const Eigen::MatrixX3d& deformed) const;

private:
    // Each template vertex's target vertex nearest to where `deformed` puts it.
    [[nodiscard]] std::vector<Eigen::Index> nearest_target_vertices(
        const Eigen::MatrixX3d& deformed) const;
    // ZoomOut from `correspondence` seen through `first_size` functions.
    [[nodiscard]] VertexMap zoomed_out_from(std::vector<Eigen::Index> correspondence,
                                            Eigen::Index first_size) const;

    LaplacianEigenbasis template_basis_;
    LaplacianEigenbasis target_basis_;
    PointIndex target_points_;
};

}  // namespace genflow::detail
