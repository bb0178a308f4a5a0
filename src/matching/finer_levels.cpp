// SPDX-License-Identifier: MIT
#include "matching/finer_levels.h"

#include <chrono>
#include <cmath>
#include <utility>

#include "genflow/exceptions.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/operators/mesh_size.h"
#include "matching/guided_rounds.h"
#include "matching/map_fit.h"
#include "matching/selection.h"
#include "matching/side_by_side.h"
#include "matching/stopwatch.h"
#include "matching/turned_parts.h"

namespace genflow::detail {

namespace {

// The embedding of a template level after the similarity: offsets scale and rotate with it.
Embedding moved_embedding(const Embedding& embedding, const Similarity& similarity) {
    Embedding moved = embedding;
    moved.offset = similarity.scale * embedding.offset * similarity.rotation.transpose();
    return moved;
}

}  // namespace

FinerLevels::FinerLevels(const std::vector<Level>& pyramid, const LevelFlows& flows,
                         const SpectralDescriptors* spectral, const MatchOptions& options,
                         double diagonal, const std::atomic<bool>& cancelled,
                         const Similarity& start, double stretch_weight)
    : pyramid_(pyramid),
      flows_(flows),
      spectral_(spectral),
      options_(options),
      diagonal_(diagonal),
      cancelled_(cancelled),
      start_(start),
      stretch_weight_(stretch_weight) {}

// Level l's template carried from the deformed level l + 1 (both at rest placed by the start).
TriangleMesh FinerLevels::carry_to(int l, const Eigen::MatrixX3d& coarse_deformed) const {
    return transfer(placed_template(level(l), start_), placed_template(level(l + 1), start_),
                    coarse_deformed, moved_embedding(level(l).embedding, start_));
}

// The rows of level l's template that are the coarsest template's vertices (a subset of every
// level's), in the coarsest level's order: where the coarsest level's analysis compares
// placements.
std::vector<Eigen::Index> FinerLevels::coarsest_rows(int l) const {
    std::vector<Eigen::Index> level_vertex(
        static_cast<std::size_t>(pyramid_.front().template_mesh.V.rows()));
    for (std::size_t v = 0; v < level(l).original_vertex.size(); ++v) {
        level_vertex[static_cast<std::size_t>(level(l).original_vertex[v])] =
            static_cast<Eigen::Index>(v);
    }
    std::vector<Eigen::Index> rows;
    for (const Eigen::Index original : pyramid_.back().original_vertex) {
        rows.push_back(level_vertex[static_cast<std::size_t>(original)]);
    }
    return rows;
}

// The intrinsic analyses of level l (template and target), once asked for; none if an
// eigen-solve fails (as the second opinion, which then is not asked).
const AnalysedShapes* FinerLevels::analysed_level(int l) {
    if (analysed_ != l) {
        analysed_ = l;
        try {
            level_shapes_ =
                analysed_shapes(options_.template_cache, level(l).template_mesh, level(l).target);
        } catch (const SolverError&) {
            level_shapes_.reset();
        }
    }
    return level_shapes_ ? &*level_shapes_ : nullptr;
}

// The level's flows (MatchOptions::refinement): the plain one, and those first guided
// by the eigenfunctions carried over by the map the coarsest result implies, side by side; the
// result whose coarsest vertices disagree least is kept.
FlowResult FinerLevels::refine(int l, const TriangleMesh& moved) {
    const PointDescriptors descriptors = spectral_->eigenfunction_descriptors(
        {coarsest_deformed_}, level(l).template_mesh.V, level(l).target.V,
        options_.guided.eigenfunction_guidance * diagonal_);
    // Flow k > 0 is guided at eigenfunction_guidance × 2^(1-k): 1, 1/2, ...
    const auto factor = [](std::size_t k) { return std::ldexp(1.0, 1 - static_cast<int>(k)); };
    std::vector<FlowResult> flows(static_cast<std::size_t>(options_.refinement.guidances) + 1);
    run_side_by_side(flows.size(), [&](std::size_t k) {
        if (k == 0) {
            flows[k] = flows_.flow(l, moved, options_.fine_iterations, start_, options_.prior);
            return;
        }
        const FlowResult guided =
            flows_.flow(l, moved, options_.refinement_iterations, start_, options_.prior,
                        {factor(k) * descriptors.moving, factor(k) * descriptors.fixed},
                        stretch_weight_, false);
        flows[k] = flows_.flow(l, guided.mesh, options_.fine_iterations, start_, options_.prior, {},
                               0, false);
        flows[k].steps += guided.steps;
    });
    const std::vector<Eigen::Index> rows = coarsest_rows(l);
    const KeptFlow kept = keep_lowest(flows, cancelled_, [&](const FlowResult& flow) {
        return disagreement(*spectral_, flow.mesh.V(rows, Eigen::all));
    });
    match_.refinement_guidance =
        kept.index == 0 ? 0 : factor(kept.index) * options_.guided.eigenfunction_guidance;
    // The level reports the plain d_H from `moved` on: where the plain flow started.
    const double start_distance = flows[0].energy.front();
    FlowResult flow = std::move(flows[kept.index]);
    flow.steps = kept.steps;
    flow.energy.front() = start_distance;
    return flow;
}

// The parts of the level that a fine functional map places turned over
// (MatchOptions::turn_back): turned back and flowed again, if d_H stays about as low
// (keeps_turned_back()). `rest`: the level's template at rest, placed by the start.
void FinerLevels::turn_back(int l, const TriangleMesh& rest, FlowResult& flow,
                            const VertexMap& map) {
    const std::vector<TurnedPart> parts =
        find_turned_parts(rest, flow.mesh.V, level(l).target, map);
    if (parts.empty()) {
        return;
    }
    TriangleMesh turned = flow.mesh;
    turned.V = turned_back(rest, flow.mesh.V, parts);
    FlowResult again = flows_.flow(l, turned, options_.refinement_iterations, start_,
                                   options_.prior, {}, options_.guided.stretch_weight, false);
    if (!cancelled_ && keeps_turned_back(again.energy.back(), flow.energy.back())) {
        again.steps += flow.steps;
        again.energy.front() = flow.energy.front();
        flow = std::move(again);
        match_.turned_parts = static_cast<int>(parts.size());
    }
}

// The level drawn towards where a fine map puts it, where the map does not tear off small
// pieces, and flowed again (MatchOptions::map_fit); kept by first_kept_fit(). ZoomOut finds a
// map from each of the spectrum's first sizes; the fits to them run side by side. Each further
// fit starts from the maps of the level as last fitted and must do clearly better
// (kMapFitProgress).
void FinerLevels::fit_to_map(int l, const FineSpectrum& spectrum, FlowResult& flow,
                             std::vector<VertexMap> maps) {
    // Every map of the spectrum has as many functions as the first.
    if (maps.empty() || maps.front().functions < 1 || !fits()) {
        return;
    }
    const double target_edge = mean_edge_length(level(l).target);
    const std::vector<Eigen::Index> rows = coarsest_rows(l);
    // The turning functions' agreement, 0 (not known) without the level's analyses.
    const AnalysedShapes* shapes = analysed_level(l);
    const auto rating_of = [&](const Eigen::MatrixX3d& deformed) {
        return FitRating{spectral_->discrepancy(deformed(rows, Eigen::all)),
                         shapes == nullptr ? 0.0 : limbs_placed(*shapes, deformed).agreement};
    };
    FitRating rating = rating_of(flow.mesh.V);
    for (int fit = 0; fit < options_.map_fit.max_fits && !cancelled_; ++fit) {
        if (fit > 0) {
            maps = spectrum.zoomed_out_maps(flow.mesh.V);
        }
        std::vector<FlowResult> fitted(maps.size());
        std::vector<FitRating> ratings(maps.size());
        run_side_by_side(maps.size(), [&](std::size_t k) {
            const VertexMap& map = maps[k];
            TriangleMesh drawn = flow.mesh;
            const Eigen::MatrixX3d placement = level(l).target.V(map.target_vertex, Eigen::all);
            const Eigen::VectorXd trusted =
                trusted_vertices(flow.mesh, placement, target_edge, map.resolved_area());
            drawn.V = fitted_to_map(flow.mesh, placement, kMapFitLength * diagonal_, trusted);
            fitted[k] = flows_.flow(l, drawn, options_.refinement_iterations, start_,
                                    options_.prior, {}, options_.guided.stretch_weight, false);
            ratings[k] = rating_of(fitted[k].mesh.V);
        });
        if (cancelled_) {
            return;
        }
        const std::optional<std::size_t> kept =
            first_kept_fit(rating, ratings, fit == 0 ? 0 : kMapFitProgress);
        if (!kept) {
            return;
        }
        FlowResult& again = fitted[*kept];
        again.steps += flow.steps;
        again.energy.front() = flow.energy.front();
        flow = std::move(again);
        rating = ratings[*kept];
        ++match_.map_fits;
    }
}

// Limbs the level has on each other's places (MatchOptions::limb_swaps), as the coarsest
// level's check finds them but on this level's shapes: the level drawn towards the landmark map
// of the exchanged extremities flows again, kept by keeps_limb_exchange(). A limb the coarsest
// level put on another's place by turning it about its joint keeps the surface's orientation,
// so that check cannot see it; the fits to the fine map, whose left and right are
// interchangeable, then reflect it into its place, where this one can. Its flow is the coarsest
// level's length (MatchOptions::max_iterations): a limb moves far. It asks nothing of where the
// exchanged extremities end: their places come from a result with its limbs swapped, and one
// may be at the wrong tip. Returns whether it exchanged any.
bool FinerLevels::exchange_limbs(int l, FlowResult& flow) {
    const AnalysedShapes* shapes = analysed_level(l);
    if (shapes == nullptr) {
        return false;
    }
    const auto& [from, to] = *shapes;
    const SwappedLimbs swapped = find_swapped_limbs(from, to, limbs_placed(*shapes, flow.mesh.V),
                                                    kLimbSwapMargin, kLimbSwapAgreement);
    const std::optional<Eigen::MatrixX3d> exchanged =
        exchanged_placement(level(l).template_mesh, from, to, swapped);
    if (!exchanged) {
        return false;
    }
    TriangleMesh drawn = flow.mesh;
    drawn.V = fitted_to_map(flow.mesh, *exchanged, kMapFitLength * diagonal_);
    FlowResult again = flows_.flow(l, drawn, options_.max_iterations, start_, options_.prior, {},
                                   options_.guided.stretch_weight, false);
    const LimbPlacement rematched = limbs_placed(*shapes, again.mesh.V);
    const std::vector<Eigen::Index> rows = coarsest_rows(l);
    if (cancelled_ ||
        !keeps_limb_exchange(
            {.agreement_before = swapped.agreement_before,
             .agreement_after = rematched.agreement,
             .disagreement_before = disagreement(*spectral_, flow.mesh.V(rows, Eigen::all)),
             .disagreement_after = disagreement(*spectral_, again.mesh.V(rows, Eigen::all))})) {
        return false;
    }
    again.steps += flow.steps;
    again.energy.front() = flow.energy.front();
    flow = std::move(again);
    match_.swapped_limbs += static_cast<int>(swapped.exchanged.size());
    return true;
}

// After the second coarsest level's flows: turned-over parts turned back and the fits to a fine map
// (one map serves both), then limbs exchanged back, which are fitted to the fine map again, now
// from their places.
void FinerLevels::refine_further(int l, FlowResult& flow) {
    std::optional<FineSpectrum> spectrum;
    if ((options_.turn_back.enabled || fits()) && !cancelled_) {
        const TriangleMesh rest = placed_template(level(l), start_);
        spectrum.emplace(rest, level(l).target);
        std::vector<VertexMap> maps = spectrum->zoomed_out_maps(flow.mesh.V);
        if (options_.turn_back.enabled) {
            turn_back(l, rest, flow, maps.front());
        }
        if (!cancelled_) {
            fit_to_map(l, *spectrum, flow, std::move(maps));
        }
    }
    if (options_.limb_swaps.enabled && !cancelled_ && exchange_limbs(l, flow) && spectrum) {
        fit_to_map(l, *spectrum, flow, spectrum->zoomed_out_maps(flow.mesh.V));
    }
}

FinerMatch FinerLevels::match(const Eigen::MatrixX3d& coarsest, StageClock& clock) {
    coarsest_deformed_ = coarsest;
    const int count = static_cast<int>(pyramid_.size());
    // The second coarsest level is the first to resolve what the coarsest could not (a hand,
    // a turned forearm) and still coarse enough for dense functional maps: in guided matches it
    // is refined and checked, each stage by its own switch.
    const bool guided = runs_guided_rounds(options_);
    const bool refines = guided && options_.guided.eigenfunction_guidance > 0 &&
                         options_.refinement.enabled && options_.refinement.guidances > 0;
    Eigen::MatrixX3d current = coarsest;
    for (int l = count - 2; l >= 0 && !cancelled_; --l) {
        const auto level_start = std::chrono::steady_clock::now();
        const TriangleMesh moved = carry_to(l, current);
        flows_.tell(l, "carried", moved);
        const bool refined_level = refines && l == count - 2;
        const bool checked_level = guided && l == count - 2;
        FlowResult flow =
            refined_level ? refine(l, moved)
                          : flows_.flow(l, moved, options_.fine_iterations, start_, options_.prior);
        flows_.tell(l, "flowed", flow.mesh);
        clock.end(refined_level ? "refinement" : "finer flows");
        if (checked_level) {
            refine_further(l, flow);
            clock.end("refined level checks");
        }
        match_.levels.push_back(level_report(level(l), flow, seconds_since(level_start)));
        flows_.tell(l, "done", flow.mesh);
        current = std::move(flow.mesh.V);
    }
    // Once cancelled, the last result carried up to the input's resolution so the output keeps
    // its vertices.
    for (int l = count - 2 - static_cast<int>(match_.levels.size()); l >= 0; --l) {
        current = carry_to(l, current).V;
    }
    match_.deformed = std::move(current);
    return std::move(match_);
}

}  // namespace genflow::detail
