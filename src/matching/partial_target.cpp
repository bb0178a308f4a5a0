// SPDX-License-Identifier: MIT
#include "matching/partial_target.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/exceptions.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/matching/partial_target.h"
#include "genflow/operators/area.h"
#include "genflow/operators/hole_area.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/normals.h"
#include "matching/intrinsic_stages.h"
#include "operators/triangle.h"

namespace genflow {

const char* to_string(TargetExtent extent) {
    switch (extent) {
        case TargetExtent::Automatic:
            return "auto";
        case TargetExtent::Complete:
            return "complete";
        case TargetExtent::Partial:
            return "partial";
    }
    return "unknown";
}

std::optional<TargetExtent> parse_target_extent(const std::string& name) {
    for (const TargetExtent extent :
         {TargetExtent::Automatic, TargetExtent::Complete, TargetExtent::Partial}) {
        if (name == to_string(extent)) {
            return extent;
        }
    }
    return std::nullopt;
}

namespace {

// The target is partial when its holes take more than this share of its closed surface beyond
// the template's: between the 0.10 that twenty palm-sized holes in a body measured at most and
// the 0.27 of a single view from above, the flattest measured (docs/benchmarks.md).
constexpr double kPartialHoleShare = 0.2;

// The share of a mesh's closed surface its holes take: 0 for a closed mesh, the same at any
// scale.
double hole_share(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "shows_part_only");
    const double area = surface_area(mesh);
    if (!(area > 0)) {
        throw InvalidInput("shows_part_only: a mesh has zero area");
    }
    const double holes = hole_area(mesh);
    return holes / (area + holes);
}

}  // namespace

bool shows_part_only(const TriangleMesh& template_mesh, const TriangleMesh& target) {
    return hole_share(target) - hole_share(template_mesh) > kPartialHoleShare;
}

namespace detail {

bool matches_partial_target(const MatchOptions& options) {
    return options.partial.extent == TargetExtent::Partial;
}

MatchOptions resolved_for_target(const MatchOptions& options, const TriangleMesh& template_mesh,
                                 const TriangleMesh& target) {
    MatchOptions resolved = options;
    if (resolved.partial.extent == TargetExtent::Automatic) {
        resolved.partial.extent =
            shows_part_only(template_mesh, target) ? TargetExtent::Partial : TargetExtent::Complete;
    }
    if (!matches_partial_target(resolved)) {
        return resolved;
    }
    // Signatures, eigenfunctions and the maps they imply read a boundary as a shape's edge: on
    // half a surface they guide the template to the wrong places (docs/matching.md).
    resolved = without_intrinsic_stages(resolved);
    // Every target point near the template; the template's scale as it is, since the areas'
    // ratio is the share the target shows, not a scale.
    resolved.starts.alignment.moving_coverage = 0;
    resolved.starts.alignment.allow_scaling = false;
    return resolved;
}

namespace {

// One side of the facing distance: points with their masses and unit normals.
struct FacingSide {
    Eigen::MatrixX3d points;
    Eigen::VectorXd masses;
    Eigen::MatrixX3d normals;
};

FacingSide facing_side(const TriangleMesh& mesh) {
    return {mesh.V, lumped_masses(mesh, MassType::Barycentric), vertex_normals(mesh)};
}

// The template's side moved by `start`: a similarity turns the normals with the points, and the
// normalized masses do not change with its scale.
FacingSide placed_side(const FacingSide& template_side, const Similarity& start) {
    return {start.apply(template_side.points), template_side.masses,
            template_side.normals * start.rotation.transpose()};
}

// The one-sided d_H from the target to the placed template, its points compared with their
// normals (PartialTargetOptions::normal_weight): low where the template covers the target facing
// the same way.
double facing_distance(const FacingSide& placed, const FacingSide& target,
                       const PseudoHausdorffOptions& distance, double normal_weight) {
    const PointDescriptors facing{normal_weight * placed.normals, normal_weight * target.normals};
    return pseudo_hausdorff(placed.points, placed.masses, target.points, target.masses, distance,
                            facing)
        .value;
}

}  // namespace

void rank_by_facing_distance(std::vector<Similarity>& starts, const TriangleMesh& template_mesh,
                             const TriangleMesh& target, const MatchOptions& options) {
    // On copies of about coarse_vertices vertices: the ranking judges the placement of the whole,
    // and on a scan of 40K points the full sums took minutes.
    const auto coarse = [&](const TriangleMesh& mesh) {
        return mesh.V.rows() > options.coarse_vertices ? coarsen(mesh, options.coarse_vertices).mesh
                                                       : mesh;
    };
    const TriangleMesh coarse_target = coarse(target);
    const FacingSide template_side = facing_side(coarse(template_mesh));
    const FacingSide target_side = facing_side(coarse_target);
    // The rigid alignment's exponent, low: the bulk of the shape decides, not a limb that moved.
    const PseudoHausdorffOptions distance{.alpha = options.starts.alignment.alpha,
                                          .epsilon = mean_edge_length(coarse_target),
                                          .truncation = 1e-2,
                                          .weights = HausdorffWeights::Normalized,
                                          .moving_coverage = 0};
    const double normal_weight =
        options.partial.normal_weight * bounding_box_diagonal(coarse_target);
    std::vector<std::pair<double, Similarity>> ranked;
    for (const Similarity& start : starts) {
        ranked.emplace_back(facing_distance(placed_side(template_side, start), target_side,
                                            distance, normal_weight),
                            start);
    }
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t k = 0; k < starts.size(); ++k) {
        starts[k] = ranked[k].second;
    }
}

}  // namespace detail

}  // namespace genflow
