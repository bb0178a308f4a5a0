// SPDX-License-Identifier: MIT
#include "matching/guided_rounds.h"

#include <cmath>

#include "matching/selection.h"
#include "matching/side_by_side.h"

namespace genflow::detail {

bool runs_guided_rounds(const MatchOptions& options) {
    return options.guided.enabled && options.guided.signature_guidance > 0 &&
           (options.prior == MatchPrior::H1 || options.prior == MatchPrior::Articulated ||
            options.prior == MatchPrior::Isometric);
}

MatchPrior guided_prior(MatchPrior prior) {
    return prior == MatchPrior::Isometric ? MatchPrior::H1 : prior;
}

GuidedRounds::GuidedRounds(const std::vector<Level>& pyramid, const LevelFlows& flows,
                           const SpectralDescriptors& spectral, const MatchOptions& options,
                           double diagonal, const std::atomic<bool>& cancelled)
    : pyramid_(pyramid),
      flows_(flows),
      spectral_(spectral),
      options_(options),
      diagonal_(diagonal),
      cancelled_(cancelled),
      prior_(guided_prior(options.prior)),
      signatures_(spectral.signature_descriptors(pyramid.back().template_mesh.V,
                                                 pyramid.back().target.V,
                                                 options.guided.signature_guidance * diagonal)) {}

// The guided flow, then the plain one; the result counts the steps of both.
FlowResult GuidedRounds::guided_then_plain(const TriangleMesh& from, const Similarity& placement,
                                           const PointDescriptors& descriptors,
                                           double stretch_weight, bool reports) const {
    FlowResult guided = flows_.flow(flows_.coarsest(), from, options_.max_iterations, placement,
                                    prior_, descriptors, stretch_weight, reports);
    if (cancelled_) {
        return guided;
    }
    FlowResult plain = flows_.flow(flows_.coarsest(), guided.mesh, options_.max_iterations,
                                   placement, prior_, {}, stretch_weight, reports);
    plain.steps += guided.steps;
    return plain;
}

// The last round, at each stiffness of MatchOptions::guided.stiffness_candidates and with each of
// `guidances` (descriptors and their weight), side by side: the stiffer ones settle at
// stretch_weight after their plain flow; the result that disagrees least with the target
// intrinsically is kept.
GuidedMatch GuidedRounds::last_round(const TriangleMesh& from, const Similarity& placement,
                                     const Guidances& guidances, int first_steps,
                                     bool reports) const {
    const auto stiffnesses = static_cast<std::size_t>(
        options_.guided.stretch_weight > 0 ? options_.guided.stiffness_candidates : 1);
    std::vector<FlowResult> flows(stiffnesses * guidances.size());
    const auto weight = [&](std::size_t t) {
        return options_.guided.stretch_weight * std::pow(4.0, static_cast<double>(t % stiffnesses));
    };
    run_side_by_side(flows.size(), [&](std::size_t t) {
        flows[t] = guided_then_plain(from, placement, guidances[t / stiffnesses].first, weight(t),
                                     reports && t == 0);
        if (t % stiffnesses > 0 && !cancelled_) {
            FlowResult settled =
                flows_.flow(flows_.coarsest(), flows[t].mesh, options_.max_iterations, placement,
                            prior_, {}, options_.guided.stretch_weight, false);
            settled.steps += flows[t].steps;
            flows[t] = std::move(settled);
        }
    });
    const KeptFlow kept = keep_lowest(flows, cancelled_, [&](const FlowResult& flow) {
        return disagreement(spectral_, flow.mesh.V);
    });
    GuidedMatch outcome;
    outcome.flow = std::move(flows[kept.index]);
    outcome.flow.steps = first_steps + kept.steps;
    outcome.stretch_weight = weight(kept.index);
    outcome.eigenfunction_guidance = guidances[kept.index / stiffnesses].second;
    outcome.disagreement = kept.rating;
    return outcome;
}

// The first round guided by the signatures; the last by the eigenfunctions carried over by the
// functional map it implies (MatchOptions::guided.eigenfunction_guidance). The stretching energy
// joins the last round only: the first serves to estimate the map, which it made worse
// (MatchOptions::guided.stretch_weight).
GuidedMatch GuidedRounds::eigenfunction_rounds(const GuidedStart& start, const TriangleMesh& from,
                                               bool reports) const {
    const FlowResult first = guided_then_plain(from, start.placement, signatures_, 0, reports);
    if (cancelled_) {
        return {.flow = first};
    }
    // The descriptors' spread is their weight: the map is estimated once and the stronger
    // guidances are its descriptors scaled (2^j, exactly). The map is estimated from this
    // match, the start's selection flow and its intrinsic placement; SpectralDescriptors keeps
    // the best of the maps ZoomOut finds.
    std::vector<Eigen::MatrixX3d> placements{first.mesh.V};
    for (const Eigen::MatrixX3d* other : {start.selection, start.intrinsic}) {
        if (other != nullptr) {
            placements.push_back(*other);
        }
    }
    const Level& level = pyramid_.back();
    const PointDescriptors descriptors =
        spectral_.eigenfunction_descriptors(placements, level.template_mesh.V, level.target.V,
                                            options_.guided.eigenfunction_guidance * diagonal_);
    Guidances guidances;
    for (int j = 0; j < options_.guided.guidance_candidates; ++j) {
        const double factor = 1 << j;
        guidances.emplace_back(
            PointDescriptors{factor * descriptors.moving, factor * descriptors.fixed},
            factor * options_.guided.eigenfunction_guidance);
    }
    GuidedMatch outcome = last_round(from, start.placement, guidances, first.steps, reports);
    // The eigenfunctions are only as right as the map that carried them: one fitted to a poor
    // first match can fold a part onto itself (a torso front to back, which d_H and the edges'
    // lengths do not mind). A doubtful round runs again guided by the signatures alone, which
    // replaces it if it disagrees less. They cannot tell left from right; the check for swapped
    // limbs that follows can.
    if (options_.guided.signature_fallback && !cancelled_ &&
        needs_signature_fallback(outcome.disagreement)) {
        GuidedMatch fallback = last_round(from, start.placement, {{signatures_, 0.0}}, 0, reports);
        const int steps = outcome.flow.steps + fallback.flow.steps;
        if (!cancelled_ && fallback.disagreement < outcome.disagreement) {
            outcome = std::move(fallback);
            outcome.signatures_alone = true;
        }
        outcome.flow.steps = steps;
    }
    return outcome;
}

GuidedMatch GuidedRounds::match(const GuidedStart& start, bool reports) const {
    const TriangleMesh from =
        start.from != nullptr ? *start.from : placed_template(pyramid_.back(), start.placement);
    GuidedMatch outcome;
    if (!start.signatures_alone && options_.guided.eigenfunction_guidance > 0) {
        outcome = eigenfunction_rounds(start, from, reports);
    } else {
        outcome = last_round(from, start.placement, {{signatures_, 0.0}}, 0, reports);
        outcome.signatures_alone = start.signatures_alone;
    }
    // The level reports the plain d_H, from the start on.
    const PseudoHausdorffEnergy plain_distance = flows_.distance_to_target(pyramid_.back(), 1, {});
    outcome.flow.energy.insert(outcome.flow.energy.begin(), plain_distance.value(from));
    outcome.flow.energy.back() = plain_distance.value(outcome.flow.mesh);
    return outcome;
}

}  // namespace genflow::detail
