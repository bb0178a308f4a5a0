// SPDX-License-Identifier: MIT
#include "matching/prepare.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "genflow/exceptions.h"
#include "genflow/operators/area.h"
#include "genflow/smoothing/smoothing.h"
#include "matching/analysis_store.h"
#include "matching/partial_target.h"
#include "matching/similarity_scale.h"
#include "matching/stopwatch.h"

namespace genflow::detail {

namespace {

// With landmarks, the starts ordered by how near they put the landmarks to their points, led
// by the landmarks' own similarity: a start that contradicts them is a wrong one, whatever d_H
// says of it (a body turned about fits d_H about as well).
void steer_by_landmarks(std::vector<Similarity>& starts, const std::vector<Landmark>& landmarks,
                        const Eigen::MatrixX3d& template_vertices) {
    // Each start's residual once, from the landmarks' own vertices alone.
    Eigen::MatrixX3d at_landmarks(static_cast<Eigen::Index>(landmarks.size()), 3);
    std::vector<Landmark> by_row = landmarks;
    for (std::size_t k = 0; k < landmarks.size(); ++k) {
        at_landmarks.row(static_cast<Eigen::Index>(k)) = template_vertices.row(landmarks[k].vertex);
        by_row[k].vertex = static_cast<Eigen::Index>(k);
    }
    std::vector<std::pair<double, Similarity>> ranked;
    for (const Similarity& start : starts) {
        ranked.emplace_back(landmark_mean_squared_distance(by_row, start.apply(at_landmarks)),
                            start);
    }
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    starts.clear();
    if (const std::optional<Similarity> fit = landmark_similarity(landmarks, template_vertices)) {
        starts.push_back(*fit);
    }
    for (const auto& [residual, start] : ranked) {
        starts.push_back(start);
    }
}

// The rigid starts, best first: the MatchOptions::starts.candidates best distinct rigid
// fits (with landmarks, those that place them best; onto a partial target, the one the facing
// distance ranks first), or the identity alone without alignment.
std::vector<Similarity> rigid_starts(const TriangleMesh& template_mesh, const TriangleMesh& target,
                                     const MatchOptions& options) {
    if (!options.starts.enabled) {
        return {Similarity{}};
    }
    RigidAlignmentOptions alignment = options.starts.alignment;
    alignment.best_starts = std::max(alignment.best_starts, options.starts.candidates);
    if (options.starts.candidates > 1) {
        alignment.refine_iterations = 0;  // the flows below decide; refining merges starts
    }
    std::vector<Similarity> starts;
    for (const RigidAlignment& candidate :
         rigid_alignment_candidates(template_mesh, target, alignment)) {
        starts.push_back(candidate.transform);
    }
    const bool partial = matches_partial_target(options);
    if (partial) {
        rank_by_facing_distance(starts, template_mesh, target, options);
    }
    if (!options.landmarks.points.empty()) {
        steer_by_landmarks(starts, options.landmarks.points, template_mesh.V);
    }
    // Onto a partial target the ranking chose: the selection flows' judge, the signatures, would
    // read the boundary as the shape's.
    const std::size_t kept = partial ? 1 : static_cast<std::size_t>(options.starts.candidates);
    starts.resize(std::min(starts.size(), kept));
    return starts;
}

// A template level's next coarser level and where the level lies on it.
struct CoarserLevel {
    CoarseMesh coarse;
    Embedding embedding;
};

CoarserLevel coarser_level(const TriangleMesh& finer, Eigen::Index size) {
    CoarseMesh coarse = coarsen(finer, size);
    Embedding embedding = embed(finer, coarse);
    return {std::move(coarse), std::move(embedding)};
}

// Finest first. The template levels are nested (each coarsened from the previous), so their
// vertices are subsets of the finer ones; each target level has about as many vertices as
// the template level when the inputs are alike, and never fewer than half.
// `coarse_source`: what the coarsest target level is coarsened from (the target, or the
// target smoothed); the others are coarsened from the target.
std::vector<Level> build_pyramid(const TriangleMesh& template_mesh, const TriangleMesh& target,
                                 const TriangleMesh& coarse_source, const MatchOptions& options) {
    int count = options.levels;
    if (count <= 0) {
        count = 1;
        for (double n = static_cast<double>(template_mesh.V.rows());
             n > 1.5 * static_cast<double>(options.coarse_vertices); n /= 4) {
            ++count;
        }
    }
    std::vector<Eigen::Index> identity(static_cast<std::size_t>(template_mesh.V.rows()));
    std::iota(identity.begin(), identity.end(), 0);
    std::vector<Level> levels{{template_mesh, target, {}, identity}};
    for (int l = 1; l < count; ++l) {
        const Level& finer = levels.back();
        const Eigen::Index size = std::max<Eigen::Index>(finer.template_mesh.V.rows() / 4, 100);
        Level coarser;
        const std::shared_ptr<const CoarserLevel> next =
            cached<CoarserLevel>(options.template_cache, "coarser level", finer.template_mesh, size,
                                 [&] { return coarser_level(finer.template_mesh, size); });
        levels.back().embedding = next->embedding;
        coarser.template_mesh = next->coarse.mesh;
        for (const Eigen::Index v : next->coarse.fine_vertex) {
            coarser.original_vertex.push_back(finer.original_vertex[static_cast<std::size_t>(v)]);
        }
        // The target coarsened by the template's factor, but to no fewer than half the
        // template level's vertices (or all the target has): a target ten times sparser than
        // the template had a tenth of its vertices on every level, too few for its signatures
        // and eigenfunctions (docs/eval/results.md, "Sparse and noisy targets"); equal counts on
        // every pair instead changed near ties of the landmark sets.
        const double ratio = static_cast<double>(coarser.template_mesh.V.rows()) /
                             static_cast<double>(template_mesh.V.rows());
        const Eigen::Index target_size = std::min(
            target.V.rows(),
            std::max({static_cast<Eigen::Index>(ratio * static_cast<double>(target.V.rows())),
                      coarser.template_mesh.V.rows() / 2, Eigen::Index{100}}));
        coarser.target = coarsen(l == count - 1 ? coarse_source : target, target_size).mesh;
        levels.push_back(std::move(coarser));
    }
    return levels;
}

}  // namespace

Prepared prepare(const TriangleMesh& template_mesh, const TriangleMesh& target,
                 const MatchOptions& options, StageClock& clock) {
    Prepared prepared;
    prepared.starts = rigid_starts(template_mesh, target, options);
    // Where the areas mislead (a rough target or template), the intrinsic starts take the
    // volumes' scale, as the rigid starts do (similarity_scale.h).
    const double area_scale = std::sqrt(surface_area(target) / surface_area(template_mesh));
    if (options.starts.enabled && options.starts.alignment.allow_scaling) {
        prepared.volume_scale = volume_scale_where_areas_mislead(template_mesh, target, area_scale);
    }
    clock.end("alignment");

    // A target rougher than its shape (more area than its volume gives it) has its coarsest
    // level made from it smoothed by a step of implicit fairing (Δt = 0.5 h²): QEM keeps much
    // of a scan's noise, whose signatures and eigenfunctions then tied right and front-to-back
    // matches (docs/eval/results.md, "Sparse and noisy targets"). The finer levels keep the
    // target as it is: smoothed, they followed the fairing's shrinkage.
    std::optional<TriangleMesh> smoothed_target;
    if (prepared.volume_scale && area_scale > *prepared.volume_scale) {
        try {
            smoothed_target = implicit_fairing(target, {.time_step = 0.5, .steps = 1}).mesh;
        } catch (const SolverError&) {
            // The target as it is, then.
        }
    }
    prepared.pyramid =
        build_pyramid(template_mesh, target, smoothed_target ? *smoothed_target : target, options);
    clock.end("pyramid");
    return prepared;
}

TriangleMesh placed_template(const Level& level, const Similarity& placement) {
    TriangleMesh placed = level.template_mesh;
    placed.V = placement.apply(placed.V);
    return placed;
}

}  // namespace genflow::detail
