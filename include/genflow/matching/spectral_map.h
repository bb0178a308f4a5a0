// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "genflow/mesh.h"

namespace genflow {

/// Parameters of spectral_map(). The weights are those of Ren et al. 2018 on operators and
/// descriptors normalized per shape, so they hold for any mesh size and scale.
struct SpectralMapOptions {
    /// Sizes of the basis in which the map is first estimated from the descriptors, tried in
    /// this order; the first whose refined map preserves the orientation is kept (the fewest
    /// functions first: they are the least changed by a pose, so the descriptors pin their map
    /// down best, but they tell fewer parts apart).
    std::vector<Eigen::Index> basis_sizes{10, 20, 30};
    /// ZoomOut (Melzi et al. 2019) refines each map up to this many eigenfunctions.
    Eigen::Index refined_size = 100;
    /// Energies of the wave kernel signatures (wave_kernel_signature()); `operator_descriptors`
    /// of them, evenly spread, give the operators that the map should commute with and that
    /// judge its orientation.
    Eigen::Index descriptors = 100;
    Eigen::Index operator_descriptors = 10;
    /// The signed descriptors ⟨n, ∇f × ∇g⟩ of the pairs of these signatures (indices into the
    /// energies; low to high frequencies) join the descriptors, smoothed onto the lowest
    /// `smoothing_size` eigenfunctions. They are what makes the estimate orientation-aware.
    std::vector<Eigen::Index> signed_bands{5, 20, 40, 60, 80};
    Eigen::Index smoothing_size = 50;
    /// Weights of the estimate's energy: descriptors preserved, commutativity with their
    /// multiplication operators, and with the Laplacian (its spectrum's mask).
    double descriptor_weight = 0.1;
    double commutativity_weight = 1;
    double laplacian_weight = 1e-3;
    /// The basis size in which a map's orientation is judged (orientation_ratio).
    Eigen::Index orientation_size = 30;
    /// ZoomOut's nearest-neighbour searches run from this many vertices of `from`, spread over
    /// it, against every vertex of `to` (a search costs their product times the functions);
    /// the last map then places every vertex. A few per function fit a map as well as all.
    Eigen::Index samples = 1000;
    /// Meshes with more vertices are analysed coarsened to about this many (coarsen()): the
    /// eigen-solve and the last search grow with #V, and 100 eigenfunctions resolve no finer.
    /// Each vertex of `from` then goes where the map puts the corner of its coarse face
    /// (embed()) that it lies nearest to. Coarsening a 5,000-vertex human to 2,000 cost
    /// accuracy and orientation (docs/benchmarks.md), so the default analyses such meshes whole.
    Eigen::Index vertices = 20000;
};

/// An intrinsic, orientation-preserving vertex-to-vertex map from `from` to `to`, blind to pose
/// and to rigid motion and scale: a functional map (Ovsjanikov et al. 2012) between the
/// shapes' Laplacian eigenbases that preserves their wave kernel signatures and the signed
/// descriptors made from them, and commutes with the Laplacian and with the signatures'
/// multiplication operators, then refined by ZoomOut. Of the maps from each of
/// SpectralMapOptions::basis_sizes, the first that preserves orientation is kept: the one that
/// commutes with the signatures' orientation operators (Ren et al. 2018) better than it
/// anticommutes with them, as a reflection does.
struct SpectralMap {
    std::vector<Eigen::Index> target_vertex;  ///< per vertex of `from`, a vertex of `to`
    /// The final functional map in the convention of the embedding: row i of Φ_from·C is close
    /// to the row of Ψ_to at target_vertex[i] (refined_size × refined_size, or fewer where a
    /// mesh has fewer eigenpairs).
    Eigen::MatrixXd functional_map;
    /// Σ‖C O_to − O_from C‖² / Σ‖C O_to + O_from C‖² over the orientation operators, C the
    /// map fitted to target_vertex (orientation_size functions): below 1 the map preserves the
    /// orientation, above 1 it reverses it (docs/benchmarks.md, "Orientation"). It says nothing
    /// of other errors: a map with limbs scattered over both sides can score below 1.
    double orientation_ratio = 0;
    /// The basis size of the kept map's first estimate.
    Eigen::Index basis_size = 0;
};

/// \throws InvalidInput if a mesh is invalid, has zero area or too few vertices for
///         `basis_size`, or an option is out of range.
/// \throws SolverError if an eigen-solve or the map's solve fails.
[[nodiscard]] SpectralMap spectral_map(const TriangleMesh& from, const TriangleMesh& to,
                                       const SpectralMapOptions& options = {});

/// SpectralMap::orientation_ratio of any vertex map `target_vertex` from `from` to `to` (the
/// meshes as given, no coarsening): below 1 it preserves the surface's orientation, above 1 it
/// reverses it, as a map that puts left for right does.
/// \throws InvalidInput as spectral_map(), or if `target_vertex` does not have a vertex of `to`
///         for each vertex of `from`.
[[nodiscard]] double orientation_ratio(const TriangleMesh& from, const TriangleMesh& to,
                                       const std::vector<Eigen::Index>& target_vertex,
                                       const SpectralMapOptions& options = {});

/// orientation_ratio() of any number of maps between the same two surfaces: their spectra and
/// orientation operators are computed once, at construction.
class MapOrientation {
public:
    /// \throws InvalidInput as orientation_ratio(); SolverError if an eigen-solve fails.
    MapOrientation(const TriangleMesh& from, const TriangleMesh& to,
                   const SpectralMapOptions& options = {});
    ~MapOrientation();
    MapOrientation(MapOrientation&&) noexcept;
    MapOrientation& operator=(MapOrientation&&) noexcept;

    /// The ratio of the map `target_vertex` (a vertex of `to` per vertex of `from`).
    /// \throws InvalidInput if it is not such a map.
    [[nodiscard]] double ratio(const std::vector<Eigen::Index>& target_vertex) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace genflow
