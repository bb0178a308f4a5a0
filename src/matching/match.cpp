// SPDX-License-Identifier: MIT
#include "genflow/matching/match.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "genflow/exceptions.h"
#include "genflow/mesh/repair.h"
#include "genflow/operators/area.h"
#include "genflow/operators/mesh_size.h"
#include "matching/analysis_store.h"
#include "matching/carried_back.h"
#include "matching/coarsest_level.h"
#include "matching/counterparts.h"
#include "matching/finer_levels.h"
#include "matching/finest_bases.h"
#include "matching/flow_memo.h"
#include "matching/guided_rounds.h"
#include "matching/intrinsic_stages.h"
#include "matching/level_flow.h"
#include "matching/partial_target.h"
#include "matching/prepare.h"
#include "matching/selection.h"
#include "matching/signatures_reading.h"
#include "matching/spectral_descriptors.h"
#include "matching/spread_landmarks.h"
#include "matching/stopwatch.h"
#include "operators/triangle.h"

namespace genflow {

const char* to_string(MatchPrior prior) {
    switch (prior) {
        case MatchPrior::L2:
            return "l2";
        case MatchPrior::H1:
            return "h1";
        case MatchPrior::Rigid:
            return "rigid";
        case MatchPrior::Articulated:
            return "articulated";
        case MatchPrior::Isometric:
            return "isometric";
    }
    return "unknown";
}

std::vector<std::string> match_prior_names() {
    std::vector<std::string> names;
    for (const MatchPrior prior : kMatchPriors) {
        names.emplace_back(to_string(prior));
    }
    return names;
}

std::optional<MatchPrior> parse_match_prior(const std::string& name) {
    for (const MatchPrior prior : kMatchPriors) {
        if (name == to_string(prior)) {
            return prior;
        }
    }
    return std::nullopt;
}

MatchOptions paper_match_options() {
    MatchOptions options = detail::without_intrinsic_stages(MatchOptions{});
    options.starts.enabled = false;
    return options;
}

namespace {

// One rule on one option: whether it holds, the rule as the message states it, the value.
struct OptionRule {
    bool holds;
    const char* rule;
    double value;
};

// "nan", "inf", or the value as people write it.
std::string shown(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

// Every rule on the numbers of MatchOptions, so that a bad one is named alone.
std::vector<OptionRule> option_rules(const MatchOptions& o) {
    using detail::finite_above;
    using detail::finite_at_least;
    const auto count = [](auto n) { return static_cast<double>(n); };
    const double threshold = o.second_opinion.above;
    const double alternatives_above = o.second_opinion.alternative_starts_above;
    return {
        {o.max_iterations >= 0, "max_iterations must be >= 0", count(o.max_iterations)},
        {o.fine_iterations >= 0, "fine_iterations must be >= 0", count(o.fine_iterations)},
        {finite_above(o.max_step, 0), "max_step must be a positive number", o.max_step},
        {finite_at_least(o.stagnation_tolerance, 0), "stagnation_tolerance must be >= 0",
         o.stagnation_tolerance},
        {finite_above(o.h1_length, 0), "h1_length must be a positive number", o.h1_length},
        {o.levels >= 0, "levels must be >= 0", count(o.levels)},
        {o.coarse_vertices >= 100, "coarse_vertices must be >= 100", count(o.coarse_vertices)},
        {finite_at_least(o.coarse_epsilon, 1), "coarse_epsilon must be >= 1", o.coarse_epsilon},
        {o.refinement_iterations >= 0, "refinement_iterations must be >= 0",
         count(o.refinement_iterations)},
        {o.starts.candidates >= 1, "starts.candidates must be >= 1", count(o.starts.candidates)},
        {o.starts.selection_iterations >= 0, "starts.selection_iterations must be >= 0",
         count(o.starts.selection_iterations)},
        {finite_at_least(o.starts.selection_tolerance, 0),
         "starts.selection_tolerance must be >= 0", o.starts.selection_tolerance},
        {finite_at_least(o.guided.signature_guidance, 0), "guided.signature_guidance must be >= 0",
         o.guided.signature_guidance},
        {finite_at_least(o.guided.eigenfunction_guidance, 0),
         "guided.eigenfunction_guidance must be >= 0", o.guided.eigenfunction_guidance},
        {finite_at_least(o.guided.stretch_weight, 0), "guided.stretch_weight must be >= 0",
         o.guided.stretch_weight},
        {o.guided.stiffness_candidates >= 1, "guided.stiffness_candidates must be >= 1",
         count(o.guided.stiffness_candidates)},
        {o.guided.guidance_candidates >= 1 && o.guided.guidance_candidates <= 8,
         "guided.guidance_candidates must lie in [1, 8]", count(o.guided.guidance_candidates)},
        {o.refinement.guidances >= 0 && o.refinement.guidances <= 8,
         "refinement.guidances must lie in [0, 8]", count(o.refinement.guidances)},
        {o.map_fit.max_fits >= 0, "map_fit.max_fits must be >= 0", count(o.map_fit.max_fits)},
        {!std::isnan(threshold) && threshold >= 0, "second_opinion.above must be >= 0 or inf",
         threshold},
        {o.second_opinion.alternative_starts >= 0, "second_opinion.alternative_starts must be >= 0",
         count(o.second_opinion.alternative_starts)},
        {!std::isnan(alternatives_above) && alternatives_above >= 0,
         "second_opinion.alternative_starts_above must be >= 0 or inf", alternatives_above},
        {finite_above(o.articulated_finest_global, 0) && o.articulated_finest_global <= 1,
         "articulated_finest_global must lie in (0, 1]", o.articulated_finest_global},
        {finite_above(o.counterparts.reach, 0), "counterparts.reach must be a positive number",
         o.counterparts.reach},
        {finite_at_least(o.partial.normal_weight, 0), "partial.normal_weight must be >= 0",
         o.partial.normal_weight},
        {o.quasi_newton_memory >= 0, "quasi_newton_memory must be >= 0",
         count(o.quasi_newton_memory)},
        {o.quasi_newton_memory == 0 || !o.implicit,
         "quasi_newton_memory must be 0 with implicit steps", count(o.quasi_newton_memory)},
    };
}

void check_landmarks(const LandmarkOptions& landmarks, Eigen::Index template_vertices) {
    if (!detail::finite_at_least(landmarks.weight, 0)) {
        throw InvalidInput("match: landmarks.weight must be finite and non-negative");
    }
    for (std::size_t k = 0; k < landmarks.points.size(); ++k) {
        const Landmark& landmark = landmarks.points[k];
        if (landmark.vertex < 0 || landmark.vertex >= template_vertices ||
            !detail::all_finite(landmark.target_point)) {
            throw InvalidInput("match: landmark " + std::to_string(k) + ": template vertex " +
                               std::to_string(landmark.vertex) + " outside 0.." +
                               std::to_string(template_vertices - 1) + " or a non-finite point");
        }
        if (!detail::finite_above(landmark.weight, 0)) {
            throw InvalidInput("match: landmark " + std::to_string(k) +
                               ": weight must be positive and finite");
        }
    }
}

// The landmarks on the repaired template's vertices.
std::vector<Landmark> repaired_landmarks(const std::vector<Landmark>& landmarks,
                                         const RepairedSurface& repaired) {
    std::vector<Landmark> moved = landmarks;
    for (std::size_t k = 0; k < moved.size(); ++k) {
        const Eigen::Index vertex =
            repaired.repaired_vertex[static_cast<std::size_t>(moved[k].vertex)];
        if (vertex < 0) {
            throw InvalidInput("match: landmark " + std::to_string(k) + ": template vertex " +
                               std::to_string(moved[k].vertex) +
                               " is not on the surface matched (a component left out in repair)");
        }
        moved[k].vertex = vertex;
    }
    return moved;
}

void check_inputs(const TriangleMesh& template_mesh, const TriangleMesh& target,
                  const MatchOptions& options) {
    for (const auto& [mesh, name] : {std::pair{&template_mesh, "template"}, {&target, "target"}}) {
        detail::require_valid_mesh(*mesh, "match");
        if (mesh->F.rows() == 0) {
            throw InvalidInput(std::string("match: the ") + name +
                               " has no faces (a point cloud is matched on "
                               "point_cloud_surface()'s mesh)");
        }
        if (!(bounding_box_diagonal(*mesh) > 0)) {
            throw InvalidInput(std::string("match: the ") + name + " has zero extent");
        }
    }
    for (const OptionRule& rule : option_rules(options)) {
        if (!rule.holds) {
            throw InvalidInput("match: " + std::string(rule.rule) + ", got " + shown(rule.value));
        }
    }
    check_landmarks(options.landmarks, template_mesh.V.rows());
    if (options.prior == MatchPrior::Articulated) {
        if (!options.parts) {
            throw InvalidInput("match: the articulated prior needs a part model");
        }
        check_part_model(*options.parts, template_mesh.V.rows());
    }
}

}  // namespace

bool MatchResult::doubtful() const {
    return intrinsic_disagreement && detail::is_doubtful(*intrinsic_disagreement);
}

namespace {

// One reading of the match from the prepared pyramid: the coarsest level, then the finer ones.
MatchResult read_match(const detail::Prepared& prepared,
                       const detail::SpectralDescriptors* analysis,
                       const TriangleMesh& template_mesh, const MatchOptions& options,
                       double diagonal, std::atomic<bool>& cancelled, detail::FlowMemo& memo,
                       detail::StageClock& clock) {
    MatchResult result;
    result.alignment_seconds = clock.seconds("alignment");
    const std::vector<detail::Level>& pyramid = prepared.pyramid;
    const int count = static_cast<int>(pyramid.size());

    // The coarsest level: the template put on the target as a whole (coarsest_level.h).
    const auto level_start = std::chrono::steady_clock::now();
    const detail::LevelFlows flows(pyramid, options, diagonal, cancelled, &memo);
    detail::CoarsestMatch coarsest = detail::match_coarsest_level(
        prepared, flows, analysis, options, diagonal, cancelled, clock);
    result.initial_alignment = coarsest.start;
    result.stretch_weight = coarsest.stretch_weight;
    result.eigenfunction_guidance = coarsest.eigenfunction_guidance;
    result.signature_fallback = coarsest.signature_fallback;
    result.second_opinion = coarsest.second_opinion;
    result.second_opinion_disagreement = coarsest.second_opinion_disagreement;
    result.alternative_starts = coarsest.alternative_starts;
    result.alternative_start = coarsest.alternative_start;
    result.swapped_limbs = coarsest.swapped_limbs;
    result.levels.push_back(
        detail::level_report(pyramid.back(), coarsest.flow,
                             clock.seconds("pyramid") + detail::seconds_since(level_start)));
    flows.tell(count - 1, "coarsest", coarsest.flow.mesh);
    if (analysis != nullptr) {
        result.intrinsic_disagreement = detail::disagreement(*analysis, coarsest.flow.mesh.V);
    }

    // The finer levels: carried, refined, flowed (finer_levels.h).
    detail::FinerLevels finer(pyramid, flows, analysis, options, diagonal, cancelled,
                              coarsest.start, coarsest.stretch_weight);
    detail::FinerMatch finest = finer.match(coarsest.flow.mesh.V, clock);
    result.levels.insert(result.levels.end(), finest.levels.begin(), finest.levels.end());
    result.refinement_guidance = finest.refinement_guidance;
    result.turned_parts = finest.turned_parts;
    result.map_fits = finest.map_fits;
    result.swapped_limbs += finest.swapped_limbs;

    result.deformed = TriangleMesh{std::move(finest.deformed), template_mesh.F};
    result.hausdorff_energy = result.levels.back().energy_end;
    return result;
}

// The signatures' reading (signatures_reading.h) beside `first`: the one whose map commutes
// better is returned. Without the eigenbases (Lanczos did not converge) the first stands. The
// flows the first reading ran unguided by the eigenfunctions come from `memo`. `clock` times the
// second reading's stages apart from the first's ("signatures reading: …"), and the judge.
MatchResult judged_readings(MatchResult first, const detail::Prepared& prepared,
                            const detail::SpectralDescriptors* analysis,
                            const TriangleMesh& template_mesh, const TriangleMesh& target,
                            const detail::FinestBases& bases, const MatchOptions& options,
                            double diagonal, std::atomic<bool>& cancelled, detail::FlowMemo& memo,
                            detail::StageClock& clock) {
    clock.name_from_now("signatures reading: ");
    MatchResult reading =
        read_match(prepared, analysis, template_mesh, detail::signatures_reading_options(options),
                   diagonal, cancelled, memo, clock);
    if (cancelled) {
        clock.name_from_now("");
        return first;
    }
    const detail::ReadingJudge judge(bases, template_mesh, target,
                                     options.signatures_reading.report_orientation);
    const detail::ReadingScore first_score = judge.score(first.deformed.V);
    const detail::ReadingScore reading_score = judge.score(reading.deformed.V);
    clock.end("judge");
    clock.name_from_now("");
    MatchResult& kept =
        detail::keeps_signatures_reading(reading_score, first_score) ? reading : first;
    kept.signatures_reading = &kept == &reading;
    kept.first_commutativity = first_score.commutativity;
    kept.signatures_commutativity = reading_score.commutativity;
    kept.first_orientation = first_score.orientation_ratio;
    kept.signatures_orientation = reading_score.orientation_ratio;
    kept.other_reading = std::move(kept.signatures_reading ? first : reading).deformed.V;
    return std::move(kept);
}

// The counterparts of `result`'s deformed template on `target` (counterparts.h), or its
// closest points where the stage is off or the eigenbases could not be had.
void find_counterparts(MatchResult& result, const TriangleMesh& target,
                       const detail::FinestBases* bases, const MatchOptions& options) {
    if (options.counterparts.enabled && bases != nullptr) {
        detail::Counterparts found =
            detail::intrinsic_counterparts(bases->template_basis, bases->target_basis, target,
                                           result.deformed.V, options.counterparts);
        result.counterparts = std::move(found.points);
        result.counterparts_moved = found.moved;
        return;
    }
    result.counterparts = detail::closest_counterparts(result.deformed.V, target);
}

// MatchResult::landmark_distance of `result`'s template as `match()` returns it (in the
// input's vertices), where there are landmarks.
void report_landmarks(MatchResult& result, const LandmarkOptions& landmarks,
                      const TriangleMesh& target) {
    if (!landmarks.points.empty()) {
        result.landmark_distance =
            std::sqrt(landmark_mean_squared_distance(landmarks.points, result.deformed.V)) /
            bounding_box_diagonal(target);
    }
}

// match() on surfaces that repair_surface() leaves as they are: the pipeline's stages, each
// timed by `clock`.
MatchResult match_surfaces(const TriangleMesh& template_mesh, const TriangleMesh& target,
                           const MatchOptions& options, detail::StageClock& clock) {
    const auto start = std::chrono::steady_clock::now();
    const double diagonal = bounding_box_diagonal(target);

    // Rigid starts, scale and the pyramid (prepare.h).
    const detail::Prepared prepared = detail::prepare(template_mesh, target, options, clock);

    // The coarsest level's intrinsic analysis, which judges starts and guides the flows.
    std::optional<detail::SpectralDescriptors> spectral;
    if (prepared.starts.size() > 1 || detail::runs_guided_rounds(options)) {
        spectral.emplace(prepared.pyramid.back().template_mesh, prepared.pyramid.back().target,
                         options.template_cache);
    }
    const detail::SpectralDescriptors* analysis = spectral ? &*spectral : nullptr;
    clock.end("coarsest analysis");

    // The finest surfaces' eigenbases, for the stages that read the whole match intrinsically.
    std::optional<detail::FinestBases> bases;
    if (detail::reads_with_signatures(options) || options.counterparts.enabled) {
        bases = detail::finest_bases(template_mesh, target, options.template_cache);
    }
    clock.end("finest bases");

    // The match, read with the eigenfunctions and, where they guide it, with the signatures.
    std::atomic<bool> cancelled = false;
    detail::FlowMemo memo;
    MatchResult result =
        read_match(prepared, analysis, template_mesh, options, diagonal, cancelled, memo, clock);
    if (detail::reads_with_signatures(options) && bases && !cancelled) {
        result = judged_readings(std::move(result), prepared, analysis, template_mesh, target,
                                 *bases, options, diagonal, cancelled, memo, clock);
    }

    // Each template vertex's counterpart on the target.
    find_counterparts(result, target, bases && !cancelled ? &*bases : nullptr, options);
    clock.end("counterparts");
    result.levels.front().seconds += clock.seconds("coarsest analysis");
    result.seconds = detail::seconds_since(start);
    return result;
}

// The spread landmarks' term over the given ones' (LandmarkOptions::spread_onto_partial). A
// spread landmark is an estimate, several percent of the diagonal off, yet together they are
// the only dense map of a view: on the 100 single views of docs/benchmarks.md the seen part's
// error falls from 6.5 (one term, every landmark alike) to 5.6 at four times the weight and
// hardly further at sixteen, where the template keeps less of its volume.
constexpr double kSpreadTermWeight = 4;

// `options` with the landmarks spread over a partial target (LandmarkOptions::
// spread_onto_partial): one for each vertex the coarsest level has on the part shown, the
// resolution at which the flows first settle the template. The given landmarks keep their term,
// not diluted by the spread ones, whose own term weighs kSpreadTermWeight times as much.
MatchOptions with_spread_landmarks(MatchOptions options, const TriangleMesh& template_mesh,
                                   const TriangleMesh& target) {
    if (!detail::matches_partial_target(options) || !options.landmarks.spread_onto_partial) {
        return options;
    }
    std::vector<Landmark>& landmarks = options.landmarks.points;
    const std::size_t given = landmarks.size();
    double given_weight = 0;
    for (const Landmark& landmark : landmarks) {
        given_weight += landmark.weight;
    }
    const double shown = surface_area(target) / surface_area(template_mesh);
    const auto count = static_cast<Eigen::Index>(
        std::lround(std::min(shown, 1.0) * static_cast<double>(options.coarse_vertices)));
    landmarks = detail::spread_landmarks(template_mesh, target, landmarks, count);
    const auto spread = static_cast<double>(landmarks.size() - given);
    if (spread > 0) {
        for (std::size_t k = given; k < landmarks.size(); ++k) {
            landmarks[k].weight = kSpreadTermWeight * given_weight / spread;
        }
        options.landmarks.weight *= 1 + kSpreadTermWeight;  // the two terms' sum
    }
    return options;
}

}  // namespace

MatchResult match(const TriangleMesh& template_mesh, const TriangleMesh& target,
                  const MatchOptions& given) {
    check_inputs(template_mesh, target, given);
    detail::StageClock clock;
    MatchOptions options = with_spread_landmarks(
        detail::resolved_for_target(given, template_mesh, target), template_mesh, target);
    if (!options.template_cache) {
        // The signatures' reading asks again for the template's analyses.
        options.template_cache = std::make_shared<TemplateCache>();
    }
    const bool partial = detail::matches_partial_target(options);
    const std::shared_ptr<const RepairedSurface> template_repair =
        detail::cached<RepairedSurface>(options.template_cache, "repair", template_mesh, 0,
                                        [&] { return repair_surface(template_mesh); });
    const RepairedSurface& repaired_template = *template_repair;
    // A partial target's pieces are all surface the template must cover.
    const RepairedSurface repaired_target =
        repair_surface(target, {.largest_component_only = !partial});
    clock.end("repair");
    if (!repaired_template.changed() && !repaired_target.changed()) {
        MatchResult result = match_surfaces(template_mesh, target, options, clock);
        result.partial_target = partial;
        report_landmarks(result, given.landmarks, target);
        result.stage_times = clock.times();
        return result;
    }
    MatchOptions on_repaired = options;
    if (options.parts) {
        on_repaired.parts = restrict_to(*options.parts, repaired_template.source_vertex);
    }
    on_repaired.landmarks.points = repaired_landmarks(options.landmarks.points, repaired_template);
    MatchResult result =
        match_surfaces(repaired_template.mesh, repaired_target.mesh, on_repaired, clock);
    result.partial_target = partial;
    result.deformed =
        TriangleMesh{detail::carried_back(repaired_template, template_mesh.V, result.deformed.V),
                     template_mesh.F};
    result.counterparts = detail::carried_counterparts(repaired_template, result.counterparts,
                                                       result.deformed.V, target);
    if (result.other_reading) {
        result.other_reading =
            detail::carried_back(repaired_template, template_mesh.V, *result.other_reading);
    }
    report_landmarks(result, given.landmarks, target);
    result.template_repairs = repaired_template.summary();
    result.target_repairs = repaired_target.summary();
    clock.end("repair");
    result.stage_times = clock.times();
    return result;
}

}  // namespace genflow
