// SPDX-License-Identifier: MIT
#include "genflow/matching/match.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/exceptions.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/mesh/repair.h"
#include "genflow/operators/mesh_size.h"
#include "matching/carried_back.h"
#include "matching/fine_spectrum.h"
#include "matching/intrinsic_start.h"
#include "matching/level_flow.h"
#include "matching/map_fit.h"
#include "matching/prepare.h"
#include "matching/selection.h"
#include "matching/side_by_side.h"
#include "matching/spectral_descriptors.h"
#include "matching/swapped_limbs.h"
#include "matching/turned_parts.h"
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
    MatchOptions options;
    options.align = false;
    options.alignment_candidates = 1;
    options.signature_guidance = 0;
    options.eigenfunction_guidance = 0;
    options.stretch_weight = 0;
    options.stiffness_candidates = 1;
    options.guidance_candidates = 1;
    options.signature_fallback = false;
    options.refinement_guidances = 0;
    options.turn_back_parts = false;
    options.map_fits = 0;
    options.second_opinion_above = std::numeric_limits<double>::infinity();
    options.alternative_starts = 0;
    options.swap_limbs = false;
    return options;
}

namespace {

void check_inputs(const TriangleMesh& template_mesh, const TriangleMesh& target,
                  const MatchOptions& options) {
    for (const auto& [mesh, name] : {std::pair{&template_mesh, "template"}, {&target, "target"}}) {
        detail::require_valid_mesh(*mesh, "match");
        if (mesh->F.rows() == 0) {
            throw InvalidInput(std::string("match: the ") + name + " has no faces");
        }
        if (!(bounding_box_diagonal(*mesh) > 0)) {
            throw InvalidInput(std::string("match: the ") + name + " has zero extent");
        }
    }
    if (options.max_iterations < 0 || !detail::finite_above(options.max_step, 0) ||
        !detail::finite_at_least(options.stagnation_tolerance, 0) ||
        options.alignment_candidates < 1 || !detail::finite_above(options.h1_length, 0) ||
        options.fine_iterations < 0 || options.levels < 0 || options.coarse_vertices < 100 ||
        options.selection_iterations < 0 || !detail::finite_at_least(options.coarse_epsilon, 1) ||
        !detail::finite_at_least(options.selection_tolerance, 0) ||
        !detail::finite_at_least(options.signature_guidance, 0) ||
        !detail::finite_at_least(options.eigenfunction_guidance, 0) ||
        !detail::finite_at_least(options.stretch_weight, 0) || options.stiffness_candidates < 1 ||
        options.contenders < 1 || !detail::finite_at_least(options.contender_tolerance, 0) ||
        options.guidance_candidates < 1 || options.guidance_candidates > 8 ||
        options.refinement_guidances < 0 || options.refinement_guidances > 8 ||
        options.refinement_iterations < 0 || options.map_fits < 0 ||
        options.alternative_starts < 0 || std::isnan(options.second_opinion_above) ||
        options.second_opinion_above < 0 || std::isnan(options.alternative_starts_above) ||
        options.alternative_starts_above < 0 ||
        !detail::finite_above(options.articulated_finest_global, 0) ||
        options.articulated_finest_global > 1) {
        throw InvalidInput(
            "match: need max_iterations >= 0, fine_iterations >= 0, max_step > 0, "
            "stagnation_tolerance >= 0, alignment_candidates >= 1, h1_length > 0, levels >= 0, "
            "coarse_vertices >= 100, coarse_epsilon >= 1, selection_tolerance >= 0, "
            "signature_guidance >= 0, eigenfunction_guidance >= 0, stretch_weight >= 0, "
            "stiffness_candidates >= 1, contenders >= 1, contender_tolerance >= 0, "
            "guidance_candidates in [1, 8], refinement_guidances in [0, 8], "
            "refinement_iterations >= 0, map_fits >= 0, alternative_starts >= 0, "
            "second_opinion_above >= 0, alternative_starts_above >= 0 and "
            "articulated_finest_global in (0, 1]");
    }
    if (options.prior == MatchPrior::Articulated) {
        if (!options.parts) {
            throw InvalidInput("match: the articulated prior needs a part model");
        }
        check_part_model(*options.parts, template_mesh.V.rows());
    }
}

}  // namespace

namespace {

// MatchOptions::map_fits: the smoothing length of a fit over the target's bounding-box
// diagonal.
constexpr double kMapFitLength = 0.01;

// A template and a target analysed alike (detail::analyse_intrinsic_shape()).
using AnalysedShapes = std::pair<detail::IntrinsicShape, detail::IntrinsicShape>;

// Where a match put the template's extremities, from `deformed`: a row per vertex of the mesh
// `shapes.first` analyses (a level of the pyramid, as matched).
detail::LimbPlacement limbs_placed(const AnalysedShapes& shapes, const Eigen::MatrixX3d& deformed) {
    const auto& [from, to] = shapes;
    return detail::place_limbs(from, to, deformed(from.coarse.fine_vertex, Eigen::all));
}

double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The embedding of a template level after the similarity: offsets scale and rotate with it.
Embedding moved_embedding(const Embedding& embedding, const Similarity& similarity) {
    Embedding moved = embedding;
    moved.offset = similarity.scale * embedding.offset * similarity.rotation.transpose();
    return moved;
}

}  // namespace

bool MatchResult::doubtful() const {
    return intrinsic_disagreement && detail::is_doubtful(*intrinsic_disagreement);
}

namespace {

// match() on surfaces that repair_surface() leaves as they are.
MatchResult match_surfaces(const TriangleMesh& template_mesh, const TriangleMesh& target,
                           const MatchOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const double diagonal = bounding_box_diagonal(target);
    MatchResult result;

    const detail::Prepared prepared = detail::prepare(template_mesh, target, options);
    std::vector<Similarity> starts = prepared.starts;
    const std::optional<double>& volume_scale = prepared.volume_scale;
    result.alignment_seconds = prepared.alignment_seconds;

    const std::vector<detail::Level>& pyramid = prepared.pyramid;
    const int count = static_cast<int>(pyramid.size());
    const double pyramid_seconds = prepared.pyramid_seconds;
    auto clock = std::chrono::steady_clock::now();
    const detail::Level& coarsest = pyramid.back();
    const bool several_starts = starts.size() > 1;
    // Measured per prior (MatchOptions::signature_guidance): h1, articulated and isometric
    // gain; the quasi-rigid flow pulled a rigidly moved limb 7 % off; L2 stays the unguided
    // baseline.
    const bool guided =
        options.signature_guidance > 0 &&
        (options.prior == MatchPrior::H1 || options.prior == MatchPrior::Articulated ||
         options.prior == MatchPrior::Isometric);
    // The metric of the coarsest level's guided rounds. The quasi-isometric prior's rounds end
    // too far from the target for their disagreement to rank them (TOSCA michael 0->1: 1.9-3.7 %
    // off from the right starts, disagreeing 0.21-0.40, against 0.21-0.22 for the front-to-back
    // ones, one of which was kept, 18.9 % off in the end), so it decides in the H1 metric, as the
    // selection flows do (the right ones at 0.11, the wrong at 0.19), and then flows in its own.
    const MatchPrior guided_prior =
        options.prior == MatchPrior::Isometric ? MatchPrior::H1 : options.prior;
    std::optional<detail::SpectralDescriptors> spectral;
    PointDescriptors signature_descriptors;  // of the coarsest template level at rest
    if (several_starts || guided) {
        spectral.emplace(coarsest.template_mesh, coarsest.target);
    }
    if (guided) {
        signature_descriptors = spectral->signature_descriptors(
            coarsest.template_mesh.V, coarsest.target.V, options.signature_guidance * diagonal);
    }

    std::atomic<bool> cancelled = false;
    const detail::LevelFlows level_flows(pyramid, options, diagonal, cancelled);
    const auto distance_to_target = [&](const detail::Level& level, double epsilon_factor,
                                        const PointDescriptors& descriptors) {
        return level_flows.distance_to_target(level, epsilon_factor, descriptors);
    };
    const auto flow_level = [&](int l, const TriangleMesh& moved, int iterations,
                                const Similarity& placement, MatchPrior prior,
                                const PointDescriptors& descriptors = {}, double stretch_weight = 0,
                                bool reports = true) {
        return level_flows.flow(l, moved, iterations, placement, prior, descriptors, stretch_weight,
                                reports);
    };
    const auto report = [](const TriangleMesh& mesh, const detail::Level& level,
                           const FlowResult& flow, double seconds) {
        return MatchLevel{mesh.V.rows(),       level.target.V.rows(), flow.steps, flow.status,
                          flow.energy.front(), flow.energy.back(),    seconds};
    };

    // The coarsest level. With several rigid starts, each flows `selection_iterations` steps
    // in the H1 metric, which lets the template reach the target's surface whatever the
    // match's prior (the signatures are compared where the flow put the points); of those
    // within selection_tolerance of the lowest d_H, the one whose signatures agree best with
    // the target's goes on (MatchOptions::align) and flows in the prior's metric.
    clock = std::chrono::steady_clock::now();
    const auto placed = [&](const Similarity& similarity) {
        TriangleMesh moved = coarsest.template_mesh;
        moved.V = similarity.apply(moved.V);
        return moved;
    };
    std::size_t chosen = 0;
    std::vector<std::size_t> contenders{0};  // the starts the guided rounds decide between
    FlowResult best;
    const int selection_steps = std::min(options.selection_iterations, options.max_iterations);
    std::vector<FlowResult> selection_flows;  // one per start, with several starts
    if (several_starts) {
        selection_flows.resize(starts.size());
        detail::run_side_by_side(starts.size(), [&](std::size_t k) {
            selection_flows[k] = flow_level(count - 1, placed(starts[k]), selection_steps,
                                            starts[k], MatchPrior::H1, {}, 0, k == 0);
        });
        contenders = detail::choose_starts(selection_flows, *spectral, options.selection_tolerance,
                                           options.contender_tolerance, options.contenders);
        chosen = contenders.front();
        best = selection_flows[chosen];
    }
    if (cancelled) {
        // Keep the selection flow's result.
    } else if (guided) {
        // Each guided flow starts from the chosen start's rigid placement and is followed by one
        // on the plain d_H. (Guiding from where the previous flow ended instead was worse on
        // FAUST, the wolf and the small cat and centaur: limbs already settled on the wrong
        // surface stay there; the eigenfunctions' guidance from the signature-guided match moved
        // no paw of the horse and cats.) First guided by the signatures, then, if
        // eigenfunction_guidance, by the eigenfunctions carried over by the functional map that
        // this first match implies.
        //
        // The guided rounds from start s: the coarsest level's result (all its steps counted),
        // the stretch weight kept and how far the result disagrees with the target.
        struct GuidedMatch {
            FlowResult flow;
            double stretch_weight = 0;
            double eigenfunction_guidance = 0;
            double disagreement = 0;
            bool signatures_alone = false;  // MatchOptions::signature_fallback kept
        };
        // `intrinsic_placement`: that of the intrinsic start s, if s is one (a second opinion).
        // `start_at`: where the flows start, if not at start s's rigid placement.
        // `signatures_alone`: the last round guided by the signatures only, as the
        // signature_fallback's (for a match again from a result that came from it).
        const auto guided_match =
            [&](std::size_t s, bool reports, const Eigen::MatrixX3d* intrinsic_placement = nullptr,
                const TriangleMesh* start_at = nullptr, bool signatures_alone = false) {
                const TriangleMesh start_mesh = start_at != nullptr ? *start_at : placed(starts[s]);
                // The guided flow, then the plain one; the result counts the steps of both.
                const auto guided_then_plain = [&](const PointDescriptors& descriptors,
                                                   double stretch_weight, bool reporting) {
                    FlowResult guided_flow =
                        flow_level(count - 1, start_mesh, options.max_iterations, starts[s],
                                   guided_prior, descriptors, stretch_weight, reporting);
                    if (cancelled) {
                        return guided_flow;
                    }
                    FlowResult plain =
                        flow_level(count - 1, guided_flow.mesh, options.max_iterations, starts[s],
                                   guided_prior, {}, stretch_weight, reporting);
                    plain.steps += guided_flow.steps;
                    return plain;
                };
                // The last round, at each stiffness of MatchOptions::stiffness_candidates and with
                // each of `guidances` (descriptors and their weight), side by side: the stiffer
                // ones settle at stretch_weight after their plain flow; the result that disagrees
                // least with the target intrinsically is kept.
                const auto last_round =
                    [&](const std::vector<std::pair<PointDescriptors, double>>& guidances,
                        int first_steps) {
                        const auto stiffnesses = static_cast<std::size_t>(
                            options.stretch_weight > 0 ? options.stiffness_candidates : 1);
                        std::vector<FlowResult> flows(stiffnesses * guidances.size());
                        const auto weight = [&](std::size_t t) {
                            return options.stretch_weight *
                                   std::pow(4.0, static_cast<double>(t % stiffnesses));
                        };
                        detail::run_side_by_side(flows.size(), [&](std::size_t t) {
                            flows[t] = guided_then_plain(guidances[t / stiffnesses].first,
                                                         weight(t), reports && t == 0);
                            if (t % stiffnesses > 0 && !cancelled) {
                                FlowResult settled = flow_level(
                                    count - 1, flows[t].mesh, options.max_iterations, starts[s],
                                    guided_prior, {}, options.stretch_weight, false);
                                settled.steps += flows[t].steps;
                                flows[t] = std::move(settled);
                            }
                        });
                        const detail::KeptFlow kept =
                            detail::keep_lowest(flows, cancelled, [&](const FlowResult& flow) {
                                return detail::disagreement(*spectral, flow.mesh.V);
                            });
                        GuidedMatch outcome;
                        outcome.flow = std::move(flows[kept.index]);
                        outcome.flow.steps = first_steps + kept.steps;
                        outcome.stretch_weight = weight(kept.index);
                        outcome.eigenfunction_guidance = guidances[kept.index / stiffnesses].second;
                        outcome.disagreement = kept.rating;
                        return outcome;
                    };
                // The stretching energy joins the last round only: the first one serves to estimate
                // the functional map, which it made worse (MatchOptions::stretch_weight).
                GuidedMatch outcome;
                if (!signatures_alone && options.eigenfunction_guidance > 0) {
                    const FlowResult first = guided_then_plain(signature_descriptors, 0, reports);
                    if (cancelled) {
                        outcome.flow = first;
                    } else {
                        // The descriptors' spread is their weight: the map is estimated once and
                        // the stronger guidances are its descriptors scaled (2^j, exactly).
                        // The map is estimated from this match and from the start's selection
                        // flow; SpectralDescriptors keeps the best of the maps ZoomOut finds.
                        std::vector<Eigen::MatrixX3d> placements{first.mesh.V};
                        if (s < selection_flows.size()) {
                            placements.push_back(selection_flows[s].mesh.V);
                        }
                        if (intrinsic_placement != nullptr) {
                            placements.push_back(*intrinsic_placement);
                        }
                        const PointDescriptors descriptors = spectral->eigenfunction_descriptors(
                            placements, coarsest.template_mesh.V, coarsest.target.V,
                            options.eigenfunction_guidance * diagonal);
                        std::vector<std::pair<PointDescriptors, double>> guidances;
                        for (int j = 0; j < options.guidance_candidates; ++j) {
                            const double factor = 1 << j;
                            guidances.emplace_back(PointDescriptors{factor * descriptors.moving,
                                                                    factor * descriptors.fixed},
                                                   factor * options.eigenfunction_guidance);
                        }
                        outcome = last_round(guidances, first.steps);
                        // The eigenfunctions are only as right as the map that carried them: one
                        // fitted to a poor first match can fold a part onto itself (TOSCA michael
                        // kneeling to standing: his torso front to back, which d_H and the edges'
                        // lengths do not mind). A doubtful round runs again guided by the
                        // signatures alone, which replaces it if it disagrees less. They cannot
                        // tell left from right; the check for swapped limbs that follows can.
                        if (options.signature_fallback && !cancelled &&
                            detail::needs_signature_fallback(outcome.disagreement)) {
                            GuidedMatch fallback = last_round({{signature_descriptors, 0.0}}, 0);
                            const int steps = outcome.flow.steps + fallback.flow.steps;
                            if (!cancelled && fallback.disagreement < outcome.disagreement) {
                                outcome = std::move(fallback);
                                outcome.signatures_alone = true;
                            }
                            outcome.flow.steps = steps;
                        }
                    }
                } else {
                    outcome = last_round({{signature_descriptors, 0.0}}, 0);
                    outcome.signatures_alone = signatures_alone;
                }
                // The level reports the plain d_H, from the rigid start on.
                const PseudoHausdorffEnergy plain_distance = distance_to_target(coarsest, 1, {});
                outcome.flow.energy.insert(outcome.flow.energy.begin(),
                                           plain_distance.value(start_mesh));
                outcome.flow.energy.back() = plain_distance.value(outcome.flow.mesh);
                return outcome;
            };
        // The second opinion joins the contenders from the intrinsic start; none without an
        // eigenbasis or landmarks (the first opinion then stands). Returns whether it joined.
        // The intrinsic starts of the next landmark sets wait for a doubtful result.
        std::vector<detail::IntrinsicStart> intrinsic;
        // The shapes' intrinsic analyses, once the second opinion needed them.
        std::optional<AnalysedShapes> shapes;
        const std::size_t rigid_contenders = contenders.size();
        const auto add_intrinsic_contender = [&] {
            try {
                shapes.emplace(detail::analyse_intrinsic_shape(coarsest.template_mesh),
                               detail::analyse_intrinsic_shape(coarsest.target));
                intrinsic = detail::intrinsic_starts(
                    coarsest.template_mesh, shapes->first, shapes->second,
                    1 + static_cast<std::size_t>(options.alternative_starts));
                if (volume_scale) {
                    for (detail::IntrinsicStart& intrinsic_start : intrinsic) {
                        detail::rescale(intrinsic_start, coarsest.template_mesh, *volume_scale);
                    }
                }
            } catch (const SolverError&) {
                intrinsic.clear();
            }
            if (!intrinsic.empty()) {
                starts.push_back(intrinsic.front().similarity);
                contenders.push_back(starts.size() - 1);
            }
            return !intrinsic.empty();
        };
        const auto placement_of = [&](std::size_t k) {
            return k < rigid_contenders ? nullptr : &intrinsic[k - rigid_contenders].placement;
        };
        // Asked of every match, the second opinion contends from the start, side by side with
        // the rigid contenders: it costs what one more contender does.
        if (options.second_opinion_above == 0) {
            add_intrinsic_contender();
        }
        // Starts that agreed about as well after the selection flows go through the guided
        // rounds each, side by side (their stiffness candidates then one after the other); the
        // one that ends agreeing best is kept (MatchOptions::contenders).
        std::vector<GuidedMatch> outcomes(contenders.size());
        detail::run_side_by_side(contenders.size(), [&](std::size_t k) {
            outcomes[k] = guided_match(contenders[k], k == 0, placement_of(k));
        });
        // The turning functions' agreement of outcome k with the target (swapped_limbs.h), once
        // asked for; 0 without the shapes' analyses.
        std::vector<std::optional<double>> turning_agreements;
        const auto turning = [&](std::size_t k) {
            if (!shapes) {
                return 0.0;
            }
            turning_agreements.resize(std::max(turning_agreements.size(), outcomes.size()));
            if (!turning_agreements[k]) {
                turning_agreements[k] = limbs_placed(*shapes, outcomes[k].flow.mesh.V).agreement;
            }
            return *turning_agreements[k];
        };
        // Outcome k as the keep-or-reject rules see it (selection.h).
        const auto score = [&](std::size_t k) {
            return detail::Score{
                k < rigid_contenders ? detail::StartKind::Rigid : detail::StartKind::Intrinsic,
                outcomes[k].disagreement, [&turning, k] { return turning(k); }};
        };
        // Whether outcome k goes on instead of outcome `than` (detail::replaces()).
        const auto preferred = [&](std::size_t k, std::size_t than) {
            return detail::replaces(score(k), score(than));
        };
        std::size_t kept = 0;
        for (std::size_t k = 0; k < outcomes.size(); ++k) {
            if (!cancelled && preferred(k, kept)) {
                kept = k;
            }
        }
        // Asked only of results that disagree more than a threshold above 0 (the doubtful ones
        // at kDoubtfulDisagreement), the second opinion comes after the rigid starts' guided
        // rounds, and is kept if it disagrees less (MatchOptions::second_opinion_above).
        if (!cancelled &&
            detail::needs_second_opinion(outcomes[kept].disagreement,
                                         options.second_opinion_above) &&
            add_intrinsic_contender()) {
            outcomes.push_back(
                guided_match(contenders.back(), true, placement_of(rigid_contenders)));
            if (!cancelled && preferred(outcomes.size() - 1, kept)) {
                kept = outcomes.size() - 1;
            }
        }
        if (contenders.size() > rigid_contenders) {
            result.second_opinion_disagreement = outcomes[rigid_contenders].disagreement;
            result.second_opinion = kept == rigid_contenders;
        }
        // A doubtful result, or one from the second opinion that disagrees more than right
        // matches do, is matched again from the intrinsic starts of the next landmark sets,
        // side by side; the one that disagrees least is kept (MatchOptions::alternative_starts,
        // alternative_starts_above).
        const double disagreement_kept = outcomes[kept].disagreement;
        if (!cancelled && intrinsic.size() > 1 &&
            detail::needs_alternative_starts(disagreement_kept, result.second_opinion,
                                             options.alternative_starts_above)) {
            const std::size_t first = outcomes.size();
            for (std::size_t next = 1; next < intrinsic.size(); ++next) {
                starts.push_back(intrinsic[next].similarity);
                contenders.push_back(starts.size() - 1);
            }
            outcomes.resize(contenders.size());
            detail::run_side_by_side(intrinsic.size() - 1, [&](std::size_t k) {
                outcomes[first + k] = guided_match(contenders[first + k], k == 0,
                                                   placement_of(rigid_contenders + 1 + k));
            });
            result.alternative_starts = static_cast<int>(intrinsic.size() - 1);
            for (std::size_t k = first; k < outcomes.size() && !cancelled; ++k) {
                if (preferred(k, kept)) {
                    kept = k;
                    result.second_opinion = false;
                    result.alternative_start = static_cast<int>(k - first + 1);
                }
            }
        }
        // Limbs the kept result put on each other's places (MatchOptions::swap_limbs): matched
        // again from the result drawn towards the map of the exchanged extremities, kept if
        // that match keeps the exchanges, its turning functions agree clearly better and as a
        // right map's do, and its signatures about as well.
        if (!cancelled && options.swap_limbs && shapes) {
            const detail::IntrinsicShape& from = shapes->first;
            const detail::IntrinsicShape& to = shapes->second;
            const TriangleMesh& matched = outcomes[kept].flow.mesh;
            const detail::SwappedLimbs swapped =
                detail::find_swapped_limbs(from, to, limbs_placed(*shapes, matched.V),
                                           detail::kLimbSwapMargin, detail::kLimbSwapAgreement);
            const std::optional<Eigen::MatrixX3d> exchanged =
                detail::exchanged_placement(coarsest.template_mesh, from, to, swapped);
            if (exchanged) {
                TriangleMesh drawn = matched;
                drawn.V = detail::fitted_to_map(matched, *exchanged, kMapFitLength * diagonal);
                starts.push_back(starts[contenders[kept]]);
                contenders.push_back(starts.size() - 1);
                outcomes.push_back(guided_match(contenders.back(), true, &*exchanged, &drawn,
                                                outcomes[kept].signatures_alone));
                const detail::LimbPlacement rematched =
                    limbs_placed(*shapes, outcomes.back().flow.mesh.V);
                if (!cancelled && detail::keeps_limb_exchange(
                                      {.agreement_before = swapped.agreement_before,
                                       .agreement_after = rematched.agreement,
                                       .disagreement_before = outcomes[kept].disagreement,
                                       .disagreement_after = outcomes.back().disagreement,
                                       .drift = detail::exchange_drift(to, swapped, rematched)})) {
                    kept = outcomes.size() - 1;
                    result.swapped_limbs = static_cast<int>(swapped.exchanged.size());
                }
            }
        }
        chosen = contenders[kept];
        int steps = 0;
        for (const GuidedMatch& outcome : outcomes) {
            steps += outcome.flow.steps;
        }
        best = std::move(outcomes[kept].flow);
        best.steps = steps;
        if (guided_prior != options.prior && !cancelled) {
            // The kept result flows on in the prior's metric, at the stiffness it was kept at;
            // the level reports the plain d_H, as the guided rounds do.
            FlowResult prior_flow =
                flow_level(count - 1, best.mesh, options.max_iterations, starts[chosen],
                           options.prior, {}, outcomes[kept].stretch_weight);
            prior_flow.steps += best.steps;
            prior_flow.energy.front() = best.energy.front();
            prior_flow.energy.back() = distance_to_target(coarsest, 1, {}).value(prior_flow.mesh);
            best = std::move(prior_flow);
        }
        result.stretch_weight = outcomes[kept].stretch_weight;
        result.eigenfunction_guidance = outcomes[kept].eigenfunction_guidance;
        result.signature_fallback = outcomes[kept].signatures_alone;
    } else if (!several_starts || options.prior != MatchPrior::H1) {
        best = flow_level(count - 1, placed(starts[chosen]), options.max_iterations, starts[chosen],
                          options.prior);
    } else if (best.status != FlowStatus::Converged && options.max_iterations > selection_steps) {
        // The H1 selection flow goes on.
        FlowResult more = flow_level(count - 1, best.mesh, options.max_iterations - selection_steps,
                                     starts[chosen], options.prior);
        more.steps += best.steps;
        more.energy.insert(more.energy.begin(), best.energy.begin(), best.energy.end() - 1);
        best = std::move(more);
    }
    const Similarity best_start = starts[chosen];
    result.initial_alignment = best_start;
    result.levels.push_back(
        report(best.mesh, coarsest, best, pyramid_seconds + seconds_since(clock)));
    const auto tell_stage = [&](int l, std::string_view stage, const TriangleMesh& mesh) {
        if (options.stages) {
            options.stages(
                {l, count, stage, &mesh, &pyramid[static_cast<std::size_t>(l)].original_vertex});
        }
    };
    tell_stage(count - 1, "coarsest", best.mesh);
    if (spectral) {
        result.intrinsic_disagreement = detail::disagreement(*spectral, best.mesh.V);
    }

    // Level l's template carried from the deformed level l + 1 (both at rest placed by the
    // chosen start).
    const auto carry_to = [&](int l, const Eigen::MatrixX3d& coarse_deformed) {
        const detail::Level& level = pyramid[static_cast<std::size_t>(l)];
        TriangleMesh rest = level.template_mesh;
        rest.V = best_start.apply(rest.V);
        TriangleMesh coarse_rest = pyramid[static_cast<std::size_t>(l + 1)].template_mesh;
        coarse_rest.V = best_start.apply(coarse_rest.V);
        return transfer(rest, coarse_rest, coarse_deformed,
                        moved_embedding(level.embedding, best_start));
    };

    // The rows of level l's template that are the coarsest template's vertices (a subset of
    // every level's), in the coarsest level's order: where `spectral` compares placements.
    const auto coarsest_rows = [&](int l) {
        const detail::Level& level = pyramid[static_cast<std::size_t>(l)];
        std::vector<Eigen::Index> level_vertex(static_cast<std::size_t>(template_mesh.V.rows()));
        for (std::size_t v = 0; v < level.original_vertex.size(); ++v) {
            level_vertex[static_cast<std::size_t>(level.original_vertex[v])] =
                static_cast<Eigen::Index>(v);
        }
        std::vector<Eigen::Index> rows;
        for (const Eigen::Index original : coarsest.original_vertex) {
            rows.push_back(level_vertex[static_cast<std::size_t>(original)]);
        }
        return rows;
    };

    // The refined level's intrinsic analyses (template and target), once asked for; none if an
    // eigen-solve fails (as the second opinion, which then is not asked).
    std::optional<AnalysedShapes> level_shapes;
    int analysed = -1;  // the level level_shapes analyse, if any was asked for
    const auto analysed_level = [&](int l) -> const auto* {
        if (analysed != l) {
            analysed = l;
            const detail::Level& level = pyramid[static_cast<std::size_t>(l)];
            try {
                level_shapes.emplace(detail::analyse_intrinsic_shape(level.template_mesh),
                                     detail::analyse_intrinsic_shape(level.target));
            } catch (const SolverError&) {
                level_shapes.reset();
            }
        }
        return level_shapes ? &*level_shapes : nullptr;
    };

    // The next finer level's flows (MatchOptions::refinement_guidances): the plain one, and
    // those first guided by the eigenfunctions carried over by the map the coarsest result
    // implies, side by side; the result whose coarsest vertices disagree least is kept.
    const Eigen::MatrixX3d coarsest_deformed = best.mesh.V;
    const auto refine = [&](int l, const TriangleMesh& moved) {
        const detail::Level& level = pyramid[static_cast<std::size_t>(l)];
        const PointDescriptors descriptors = spectral->eigenfunction_descriptors(
            {coarsest_deformed}, level.template_mesh.V, level.target.V,
            options.eigenfunction_guidance * diagonal);
        // Flow k > 0 is guided at eigenfunction_guidance × 2^(1-k): 1, 1/2, ...
        const auto factor = [](std::size_t k) { return std::ldexp(1.0, 1 - static_cast<int>(k)); };
        std::vector<FlowResult> flows(static_cast<std::size_t>(options.refinement_guidances) + 1);
        detail::run_side_by_side(flows.size(), [&](std::size_t k) {
            if (k == 0) {
                flows[k] = flow_level(l, moved, options.fine_iterations, best_start, options.prior);
                return;
            }
            const FlowResult guided_flow =
                flow_level(l, moved, options.refinement_iterations, best_start, options.prior,
                           {factor(k) * descriptors.moving, factor(k) * descriptors.fixed},
                           result.stretch_weight, false);
            flows[k] = flow_level(l, guided_flow.mesh, options.fine_iterations, best_start,
                                  options.prior, {}, 0, false);
            flows[k].steps += guided_flow.steps;
        });
        const std::vector<Eigen::Index> rows = coarsest_rows(l);
        const detail::KeptFlow kept =
            detail::keep_lowest(flows, cancelled, [&](const FlowResult& flow) {
                return detail::disagreement(*spectral, flow.mesh.V(rows, Eigen::all));
            });
        result.refinement_guidance =
            kept.index == 0 ? 0 : factor(kept.index) * options.eigenfunction_guidance;
        // The level reports the plain d_H from `moved` on: where the plain flow started.
        const double start_distance = flows[0].energy.front();
        FlowResult flow = std::move(flows[kept.index]);
        flow.steps = kept.steps;
        flow.energy.front() = start_distance;
        return flow;
    };

    // The parts of the refined level that a fine functional map places turned over
    // (MatchOptions::turn_back_parts): turned back and flowed again, if d_H stays about as low.
    // `rest`: the level's template at rest, placed by the chosen start.
    const auto turn_back = [&](int l, const TriangleMesh& rest, FlowResult& flow,
                               const detail::VertexMap& map) {
        const detail::Level& level = pyramid[static_cast<std::size_t>(l)];
        const std::vector<detail::TurnedPart> parts =
            detail::find_turned_parts(rest, flow.mesh.V, level.target, map);
        if (parts.empty()) {
            return;
        }
        TriangleMesh turned = flow.mesh;
        turned.V = detail::turned_back(rest, flow.mesh.V, parts);
        FlowResult again = flow_level(l, turned, options.refinement_iterations, best_start,
                                      options.prior, {}, options.stretch_weight, false);
        if (!cancelled && detail::keeps_turned_back(again.energy.back(), flow.energy.back())) {
            again.steps += flow.steps;
            again.energy.front() = flow.energy.front();
            flow = std::move(again);
            result.turned_parts = static_cast<int>(parts.size());
        }
    };

    // The refined level drawn towards where a fine map puts it, where the map does not tear
    // off small pieces, and flowed again (MatchOptions::map_fits); kept if its heat kernel
    // signatures then agree better with the target's, or its turning functions clearly better,
    // and the map was not mirrored (detail::keeps_fit()). ZoomOut finds a map from each of
    // kFineMapFirstSizes; the fits to them run side by side, and the first kept in that order
    // is kept (detail::first_kept_fit()). Each further fit starts from the maps of the level as
    // last fitted and must do clearly better (detail::kMapFitProgress).
    const auto fit_to_map = [&](int l, const detail::FineSpectrum& spectrum, FlowResult& flow,
                                std::vector<detail::VertexMap> maps) {
        // Every map of the spectrum has as many functions as the first.
        if (maps.empty() || maps.front().functions < 1 || options.map_fits < 1) {
            return;
        }
        const detail::Level& level = pyramid[static_cast<std::size_t>(l)];
        const double target_edge = mean_edge_length(level.target);
        const std::vector<Eigen::Index> rows = coarsest_rows(l);
        // The turning functions' agreement, 0 (not known) without the level's analyses.
        const auto* shapes = analysed_level(l);
        const auto turning = [&](const Eigen::MatrixX3d& deformed) {
            return shapes == nullptr ? 0.0 : limbs_placed(*shapes, deformed).agreement;
        };
        const auto rating_of = [&](const Eigen::MatrixX3d& deformed) {
            return detail::FitRating{spectral->discrepancy(deformed(rows, Eigen::all)),
                                     turning(deformed)};
        };
        detail::FitRating rating = rating_of(flow.mesh.V);
        for (int fit = 0; fit < options.map_fits && !cancelled; ++fit) {
            if (fit > 0) {
                maps = spectrum.zoomed_out_maps(flow.mesh.V);
            }
            std::vector<FlowResult> fitted(maps.size());
            std::vector<detail::FitRating> ratings(maps.size());
            detail::run_side_by_side(maps.size(), [&](std::size_t k) {
                const detail::VertexMap& map = maps[k];
                TriangleMesh drawn = flow.mesh;
                const Eigen::MatrixX3d placement = level.target.V(map.target_vertex, Eigen::all);
                const Eigen::VectorXd trusted = detail::trusted_vertices(
                    flow.mesh, placement, target_edge, map.resolved_area());
                drawn.V =
                    detail::fitted_to_map(flow.mesh, placement, kMapFitLength * diagonal, trusted);
                fitted[k] = flow_level(l, drawn, options.refinement_iterations, best_start,
                                       options.prior, {}, options.stretch_weight, false);
                ratings[k] = rating_of(fitted[k].mesh.V);
            });
            if (cancelled) {
                return;
            }
            const std::optional<std::size_t> kept =
                detail::first_kept_fit(rating, ratings, fit == 0 ? 0 : detail::kMapFitProgress);
            if (!kept) {
                return;
            }
            FlowResult& again = fitted[*kept];
            again.steps += flow.steps;
            again.energy.front() = flow.energy.front();
            flow = std::move(again);
            rating = ratings[*kept];
            ++result.map_fits;
        }
    };

    // Limbs the refined level has on each other's places (MatchOptions::swap_limbs), as the
    // coarsest level's check finds them (swapped_limbs.h) but on this level's shapes: the
    // level drawn towards the landmark map of the exchanged extremities flows again, and is
    // kept if its turning functions agree clearly better and as a right map's do, and its
    // signatures about as well (detail::keeps_limb_exchange()).
    // A limb the coarsest level put on another's place by turning it about its joint keeps
    // the surface's orientation, so that check cannot see it; the fits to the fine map, whose
    // left and right are interchangeable, then reflect it into its place, where this one can
    // (the elephant 100 → 300, articulated: 0.48 at the coarsest level, 0.18 after the fits).
    // Its flow is the coarsest level's length (MatchOptions::max_iterations): a limb moves far.
    // Unlike that check it asks nothing of where the exchanged extremities end: their places
    // come from a result with its limbs swapped, and one may be at the wrong tip (0.72 of √area
    // from where the right result, 1.9 % off, put it). Returns whether it exchanged any; none
    // if an eigen-solve of the analyses fails (as the second opinion, which then is not asked).
    const auto exchange_limbs = [&](int l, FlowResult& flow) {
        const detail::Level& level = pyramid[static_cast<std::size_t>(l)];
        const auto* shapes = analysed_level(l);
        if (shapes == nullptr) {
            return false;
        }
        const auto& [from, to] = *shapes;
        const detail::SwappedLimbs swapped =
            detail::find_swapped_limbs(from, to, limbs_placed(*shapes, flow.mesh.V),
                                       detail::kLimbSwapMargin, detail::kLimbSwapAgreement);
        const std::optional<Eigen::MatrixX3d> exchanged =
            detail::exchanged_placement(level.template_mesh, from, to, swapped);
        if (!exchanged) {
            return false;
        }
        TriangleMesh drawn = flow.mesh;
        drawn.V = detail::fitted_to_map(flow.mesh, *exchanged, kMapFitLength * diagonal);
        FlowResult again = flow_level(l, drawn, options.max_iterations, best_start, options.prior,
                                      {}, options.stretch_weight, false);
        const detail::LimbPlacement rematched = limbs_placed(*shapes, again.mesh.V);
        const std::vector<Eigen::Index> rows = coarsest_rows(l);
        if (cancelled ||
            !detail::keeps_limb_exchange({.agreement_before = swapped.agreement_before,
                                          .agreement_after = rematched.agreement,
                                          .disagreement_before = detail::disagreement(
                                              *spectral, flow.mesh.V(rows, Eigen::all)),
                                          .disagreement_after = detail::disagreement(
                                              *spectral, again.mesh.V(rows, Eigen::all))})) {
            return false;
        }
        again.steps += flow.steps;
        again.energy.front() = flow.energy.front();
        flow = std::move(again);
        result.swapped_limbs += static_cast<int>(swapped.exchanged.size());
        return true;
    };

    // Finer levels: transfer, then a short flow.
    const bool refines =
        guided && options.eigenfunction_guidance > 0 && options.refinement_guidances > 0;
    TriangleMesh current = std::move(best.mesh);
    for (int l = count - 2; l >= 0 && !cancelled; --l) {
        clock = std::chrono::steady_clock::now();
        const detail::Level& level = pyramid[static_cast<std::size_t>(l)];
        const TriangleMesh moved = carry_to(l, current.V);
        tell_stage(l, "carried", moved);
        const bool refined_level = refines && l == count - 2;
        FlowResult flow = refined_level ? refine(l, moved)
                                        : flow_level(l, moved, options.fine_iterations, best_start,
                                                     options.prior);
        tell_stage(l, "flowed", flow.mesh);
        // One fine map serves the turn-back and the first fit.
        std::optional<detail::FineSpectrum> spectrum;
        if (refined_level && (options.turn_back_parts || options.map_fits > 0) && !cancelled) {
            TriangleMesh rest = level.template_mesh;
            rest.V = best_start.apply(rest.V);
            spectrum.emplace(rest, level.target);
            std::vector<detail::VertexMap> maps = spectrum->zoomed_out_maps(flow.mesh.V);
            if (options.turn_back_parts) {
                turn_back(l, rest, flow, maps.front());
            }
            if (!cancelled) {
                fit_to_map(l, *spectrum, flow, std::move(maps));
            }
        }
        // Limbs exchanged back are fitted to the fine map again, now from their places.
        if (refined_level && options.swap_limbs && !cancelled && exchange_limbs(l, flow) &&
            spectrum) {
            fit_to_map(l, *spectrum, flow, spectrum->zoomed_out_maps(flow.mesh.V));
        }
        result.levels.push_back(report(flow.mesh, level, flow, seconds_since(clock)));
        tell_stage(l, "done", flow.mesh);
        current = std::move(flow.mesh);
    }
    if (cancelled && static_cast<int>(result.levels.size()) < count) {
        // Carry the last result up to the input's resolution so the output keeps its vertices.
        for (int l = count - static_cast<int>(result.levels.size()) - 1; l >= 0; --l) {
            current = carry_to(l, current.V);
        }
    }
    result.deformed = TriangleMesh{current.V, template_mesh.F};
    result.hausdorff_energy = result.levels.back().energy_end;
    result.seconds = seconds_since(start);
    return result;
}

}  // namespace

MatchResult match(const TriangleMesh& template_mesh, const TriangleMesh& target,
                  const MatchOptions& options) {
    check_inputs(template_mesh, target, options);
    const RepairedSurface repaired_template = repair_surface(template_mesh);
    const RepairedSurface repaired_target = repair_surface(target);
    if (!repaired_template.changed() && !repaired_target.changed()) {
        return match_surfaces(template_mesh, target, options);
    }
    MatchOptions on_repaired = options;
    if (options.parts) {
        on_repaired.parts = restrict_to(*options.parts, repaired_template.source_vertex);
    }
    MatchResult result = match_surfaces(repaired_template.mesh, repaired_target.mesh, on_repaired);
    result.deformed =
        TriangleMesh{detail::carried_back(repaired_template, template_mesh.V, result.deformed.V),
                     template_mesh.F};
    result.template_repairs = repaired_template.summary();
    result.target_repairs = repaired_target.summary();
    return result;
}

}  // namespace genflow
