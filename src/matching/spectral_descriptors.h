// SPDX-License-Identifier: MIT
// The intrinsic (pose-blind) view of a template and a target, from the eigenbases of their
// Laplacians, for the places where a match needs to know which part of a shape is which:
// - choosing among rigid starts: after a flow, a flipped start can fit the target's surface as
//   closely as the right one (head to tail, facing backwards), but it puts template points on
//   target places of another kind (a tail tip on an ear): the heat kernel signatures tell;
// - guiding the coarsest flow: as descriptors of d_H (PointDescriptors), heat kernel signatures
//   keep a limb from settling on the wrong one nearby (a hanging arm on the hip);
// - then telling left from right: the signatures are blind to a shape's symmetries, so a left
//   paw may still land on the right one. The low eigenfunctions are not (half of them change
//   sign under a left–right reflection): a functional map estimated from the guided match, in
//   which most of the shape is on the right side, carries them from the template to the target.
// What the choices below were measured on: docs/measurements.md, "Spectral descriptors".
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/matching/template_cache.h"
#include "genflow/mesh.h"
#include "spatial/point_index.h"

namespace genflow::detail {

class SpectralDescriptors {
public:
    /// Eigenbases (laplacian_eigenbasis()) and heat kernel signatures (default times) of
    /// `template_mesh` and `target`, each coarsened to about `vertices` first (the eigen-solve
    /// is dense). The template's are kept in `template_cache`, where there is one.
    /// \throws InvalidInput if a mesh has no vertex with area.
    SpectralDescriptors(const TriangleMesh& template_mesh, const TriangleMesh& target,
                        const std::shared_ptr<TemplateCache>& template_cache = {},
                        Eigen::Index vertices = 1000);

    /// How far a placement of the template disagrees with the target: the median over the
    /// template's signature vertices i of ‖log h(i) − log h(j)‖², j the target's signature vertex
    /// nearest to where `deformed` (#V×3, the template's vertices deformed) puts i. The median,
    /// not the mean: where the two surfaces differ intrinsically (limbs in contact, fused by a
    /// scanner or remesher) the signatures change far from the contact, and those points would
    /// dominate a mean.
    /// \throws InvalidInput if `deformed` does not have the template's vertex count.
    [[nodiscard]] double discrepancy(const Eigen::MatrixX3d& deformed) const;

    /// How close the correspondence of `deformed` (each template point with the target point
    /// nearest to where it was put) comes to preserving the `functions` lowest eigenfunctions:
    /// the mean singular value of the functional map C fitted to it in the least-squares sense
    /// (φ C ≈ ψ at corresponding points). A near-isometry maps the M-orthonormal φ onto
    /// M-orthonormal functions (all singular values 1); a correspondence that folds parts onto
    /// one another (a start turned front to back, the flow then fitting the limbs wherever they
    /// are nearest) loses the functions that tell those parts apart, and their singular values
    /// fall. Scale-free, between 0 and about 1.
    /// \throws InvalidInput if `deformed` does not have the template's vertex count.
    [[nodiscard]] double map_consistency(const Eigen::MatrixX3d& deformed,
                                         int functions = 20) const;

    /// Descriptors of d_H for points of the template at rest (`template_points`, in the frame
    /// of the template given to the constructor) and of the target (`target_points`): the log
    /// signature of the nearest signature vertex, centred and divided per diffusion time by the
    /// template's mean and standard deviation, times `length`/√k (k times), so that the
    /// template's root-mean-square spread is `length`. (One scale for all times instead kept a
    /// rigidly moved limb no better under the quasi-rigid prior: its small-time signatures are
    /// mostly sampling, and the pull of those the flow cannot meet remains.)
    [[nodiscard]] PointDescriptors signature_descriptors(const Eigen::MatrixX3d& template_points,
                                                         const Eigen::MatrixX3d& target_points,
                                                         double length) const;

    /// Descriptors of d_H from the `functions` lowest non-constant eigenfunctions: the target's
    /// ψ, and the template's φ carried over by a functional map C (φ C ≈ ψ at corresponding
    /// points), each divided by √λ (the low ones vary smoothly over whole parts; the high ones
    /// are noisier and, on coarse meshes, may not correspond at all). C is estimated from the
    /// correspondence of a placement (each template point with the target point nearest to
    /// where it was put) and refined as in ZoomOut (Melzi et al. 2019): from a few functions up
    /// to `functions`, C is fitted to the correspondence and made orthogonal (a near-isometry
    /// keeps the basis orthonormal), and the correspondence becomes that of nearest neighbours
    /// in the (√λ-divided) embedding. The orthogonal fit follows the majority: a limb on the
    /// wrong side is outvoted by the rest of the shape. The descriptors are scaled so that the
    /// target's root-mean-square spread is `length`.
    ///
    /// Where ZoomOut ends depends on where it starts: from a correspondence with whole parts
    /// misplaced it ends either near the right map or near a wrong one, and which one can change
    /// with a vertex more or less in the coarse meshes. So it runs from every placement given
    /// and from 4, 6, 8 and 10 functions, and keeps the map whose own correspondence disagrees
    /// least with the target, as a match's intrinsic disagreement does: the median discrepancy
    /// of the heat kernel signatures over its final correspondence, divided by how nearly
    /// orthogonal the map is (its mean singular value, map_consistency()) less the mean
    /// distance, over the diagonal, by which it moves the points of the placement's
    /// correspondence. Orthogonality alone does not tell a map twisted half a turn about a
    /// limb's axis from the right one; the signatures do. The motion term stays for shapes whose
    /// symmetry the signatures cannot see: a map flipped about it moves the points farther.
    /// \throws InvalidInput if `placements` is empty or a placement does not have the template's
    ///         vertex count.
    [[nodiscard]] PointDescriptors eigenfunction_descriptors(
        const std::vector<Eigen::MatrixX3d>& placements, const Eigen::MatrixX3d& template_points,
        const Eigen::MatrixX3d& target_points, double length, int functions = 20) const;

private:
    Eigen::Index template_vertices_ = 0;
    std::vector<Eigen::Index> template_vertex_;  // template vertex of each signature row
    PointIndex template_points_;  // the signature vertices at rest, rows as the signatures
    PointIndex target_points_;
    Eigen::MatrixX3d target_positions_;  // the points of target_points_, rows as the signatures
    // Rows as the points above.
    Eigen::MatrixXd template_log_signature_;
    Eigen::MatrixXd target_log_signature_;
    Eigen::MatrixXd template_functions_;  // the non-constant eigenfunctions, ascending
    Eigen::MatrixXd target_functions_;
    Eigen::VectorXd template_masses_;
    Eigen::VectorXd target_values_;  // the target's non-constant eigenvalues, times its area

    // `functions` (at least 1) as far as both meshes have non-constant eigenfunctions.
    [[nodiscard]] Eigen::Index function_count(int functions) const;
    // ψ_k / √λ_k weights of the `count` lowest functions.
    [[nodiscard]] Eigen::RowVectorXd function_weights(Eigen::Index count) const;
    // ZoomOut from `correspondence` (template signature row -> target row): from `first`
    // functions up to `count`, the map fitted and made orthogonal, the correspondence that of
    // nearest neighbours in the weighted embedding.
    [[nodiscard]] std::vector<Eigen::Index> zoom_out(std::vector<Eigen::Index> correspondence,
                                                     Eigen::Index first, Eigen::Index count) const;
    // Median squared distance between the log signatures of corresponding rows.
    [[nodiscard]] double signature_discrepancy(
        const std::vector<Eigen::Index>& correspondence) const;
    // The target signature row nearest to where `deformed` puts each template signature row.
    [[nodiscard]] std::vector<Eigen::Index> nearest_target_rows(
        const Eigen::MatrixX3d& deformed) const;
};

}  // namespace genflow::detail
