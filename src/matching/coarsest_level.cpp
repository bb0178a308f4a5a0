// SPDX-License-Identifier: MIT
#include "matching/coarsest_level.h"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "genflow/exceptions.h"
#include "matching/guided_rounds.h"
#include "matching/intrinsic_start.h"
#include "matching/map_fit.h"
#include "matching/selection.h"
#include "matching/side_by_side.h"
#include "matching/swapped_limbs.h"

namespace genflow::detail {

namespace {

// The contest of the guided rounds between the chosen rigid start (outcome 0) and the intrinsic
// starts (the second opinion's is outcome 1); `kept_` indexes the outcome that goes on.
class Contest {
public:
    Contest(const Prepared& prepared, const std::vector<FlowResult>& selection_flows,
            std::size_t rigid_start, const GuidedRounds& rounds, const MatchOptions& options,
            double diagonal, const std::atomic<bool>& cancelled)
        : prepared_(prepared),
          selection_flows_(selection_flows),
          rounds_(rounds),
          options_(options),
          diagonal_(diagonal),
          cancelled_(cancelled),
          starts_(prepared.starts),
          contenders_{rigid_start} {}

    // The rigid start's rounds, side by side with the second opinion's when every match asks it
    // (MatchOptions::second_opinion = 0: it then costs what one more contender does).
    void run_contenders() {
        if (second_opinion_above() == 0) {
            add_intrinsic_contender();
        }
        outcomes_.resize(contenders_.size());
        run_side_by_side(contenders_.size(),
                         [&](std::size_t k) { outcomes_[k] = run(k, k == kRigidStart); });
        for (std::size_t k = 0; k < outcomes_.size(); ++k) {
            if (!cancelled_ && preferred(k, kept_)) {
                kept_ = k;
            }
        }
    }

    // Asked only of results that disagree more than a threshold above 0, the second opinion
    // comes after the rigid start's rounds and is kept if it disagrees less.
    void ask_second_opinion() {
        if (!cancelled_ &&
            needs_second_opinion(outcomes_[kept_].disagreement, second_opinion_above()) &&
            add_intrinsic_contender()) {
            outcomes_.push_back(run(contenders_.size() - 1, true));
            if (!cancelled_ && preferred(outcomes_.size() - 1, kept_)) {
                kept_ = outcomes_.size() - 1;
            }
        }
        if (contenders_.size() > kSecondOpinion) {
            match_.second_opinion_disagreement = outcomes_[kSecondOpinion].disagreement;
            match_.second_opinion = kept_ == kSecondOpinion;
        }
    }

    // A result that disagrees more than right matches do, from a rigid start or the second
    // opinion, matched again from the intrinsic starts of the next landmark sets, side by side;
    // the one that disagrees least is kept (MatchOptions::second_opinion.alternative_starts).
    void try_alternative_starts() {
        if (cancelled_ || intrinsic_.size() <= 1 ||
            !needs_alternative_starts(outcomes_[kept_].disagreement,
                                      options_.second_opinion.alternative_starts_above)) {
            return;
        }
        const std::size_t first = outcomes_.size();
        for (std::size_t next = 1; next < intrinsic_.size(); ++next) {
            add_contender(intrinsic_[next].similarity);
        }
        outcomes_.resize(contenders_.size());
        run_side_by_side(intrinsic_.size() - 1,
                         [&](std::size_t k) { outcomes_[first + k] = run(first + k, k == 0); });
        match_.alternative_starts = static_cast<int>(intrinsic_.size() - 1);
        for (std::size_t k = first; k < outcomes_.size() && !cancelled_; ++k) {
            if (preferred(k, kept_)) {
                kept_ = k;
                match_.second_opinion = false;
                match_.alternative_start = static_cast<int>(k - first + 1);
            }
        }
    }

    // Limbs the kept result put on each other's places (MatchOptions::limb_swaps): matched
    // again from the result drawn towards the map of the exchanged extremities; kept by
    // keeps_limb_exchange().
    void exchange_limbs() {
        if (cancelled_ || !options_.limb_swaps.enabled || !shapes_) {
            return;
        }
        const auto& [from, to] = *shapes_;
        const TriangleMesh& matched = outcomes_[kept_].flow.mesh;
        const SwappedLimbs swapped = find_swapped_limbs(from, to, limbs_placed(*shapes_, matched.V),
                                                        kLimbSwapMargin, kLimbSwapAgreement);
        const std::optional<Eigen::MatrixX3d> exchanged =
            exchanged_placement(coarsest().template_mesh, from, to, swapped);
        if (!exchanged) {
            return;
        }
        TriangleMesh drawn = matched;
        drawn.V = fitted_to_map(matched, *exchanged, kMapFitLength * diagonal_);
        add_contender(starts_[contenders_[kept_]]);
        outcomes_.push_back(rounds_.match({.placement = starts_.back(),
                                           .intrinsic = &*exchanged,
                                           .from = &drawn,
                                           .signatures_alone = outcomes_[kept_].signatures_alone},
                                          true));
        const LimbPlacement rematched = limbs_placed(*shapes_, outcomes_.back().flow.mesh.V);
        if (!cancelled_ &&
            keeps_limb_exchange({.agreement_before = swapped.agreement_before,
                                 .agreement_after = rematched.agreement,
                                 .disagreement_before = outcomes_[kept_].disagreement,
                                 .disagreement_after = outcomes_.back().disagreement,
                                 .drift = exchange_drift(to, swapped, rematched)})) {
            kept_ = outcomes_.size() - 1;
            match_.swapped_limbs = static_cast<int>(swapped.exchanged.size());
        }
    }

    // The kept outcome, with the steps of every round counted.
    CoarsestMatch finish() {
        int steps = 0;
        for (const GuidedMatch& outcome : outcomes_) {
            steps += outcome.flow.steps;
        }
        GuidedMatch& kept = outcomes_[kept_];
        match_.flow = std::move(kept.flow);
        match_.flow.steps = steps;
        match_.start = starts_[contenders_[kept_]];
        match_.stretch_weight = kept.stretch_weight;
        match_.eigenfunction_guidance = kept.eigenfunction_guidance;
        match_.signature_fallback = kept.signatures_alone;
        return std::move(match_);
    }

private:
    // The outcomes of the rigid start and of the second opinion: outcome kSecondOpinion + j is
    // intrinsic start j's (the alternative starts follow the second opinion), then the limb
    // exchange's.
    static constexpr std::size_t kRigidStart = 0;
    static constexpr std::size_t kSecondOpinion = 1;

    [[nodiscard]] const Level& coarsest() const { return prepared_.pyramid.back(); }

    // MatchOptions::second_opinion's threshold; +inf (never) when it is off.
    [[nodiscard]] double second_opinion_above() const {
        return options_.second_opinion.enabled ? options_.second_opinion.above
                                               : std::numeric_limits<double>::infinity();
    }

    void add_contender(Similarity start) {
        starts_.push_back(start);
        contenders_.push_back(starts_.size() - 1);
    }

    // The guided rounds of contender k.
    [[nodiscard]] GuidedMatch run(std::size_t k, bool reports) const {
        const std::size_t s = contenders_[k];
        return rounds_.match(
            {.placement = starts_[s],
             .selection = s < selection_flows_.size() ? &selection_flows_[s].mesh.V : nullptr,
             .intrinsic = k == kRigidStart ? nullptr : &intrinsic_[k - kSecondOpinion].placement},
            reports);
    }

    // The second opinion joins the contenders from the intrinsic start (the intrinsic starts of
    // the further landmark sets wait for a doubtful result); none without an eigenbasis or
    // landmarks, and the first opinion then stands. Returns whether it joined.
    bool add_intrinsic_contender() {
        const Level& level = coarsest();
        try {
            shapes_ = analysed_shapes(options_.template_cache, level.template_mesh, level.target);
            intrinsic_ = intrinsic_starts(
                level.template_mesh, shapes_->first, shapes_->second,
                1 + static_cast<std::size_t>(options_.second_opinion.alternative_starts));
            if (prepared_.volume_scale) {
                for (IntrinsicStart& start : intrinsic_) {
                    rescale(start, level.template_mesh, *prepared_.volume_scale);
                }
            }
        } catch (const SolverError&) {
            intrinsic_.clear();
        }
        if (!intrinsic_.empty()) {
            add_contender(intrinsic_.front().similarity);
        }
        return !intrinsic_.empty();
    }

    // The turning functions' agreement of outcome k with the target, once asked for; 0
    // without the shapes' analyses.
    double turning(std::size_t k) {
        if (!shapes_) {
            return 0.0;
        }
        turning_agreements_.resize(std::max(turning_agreements_.size(), outcomes_.size()));
        if (!turning_agreements_[k]) {
            turning_agreements_[k] = limbs_placed(*shapes_, outcomes_[k].flow.mesh.V).agreement;
        }
        return *turning_agreements_[k];
    }

    // Whether outcome k goes on instead of outcome `than` (replaces()).
    bool preferred(std::size_t k, std::size_t than) {
        const auto score = [&](std::size_t i) {
            return Score{i == kRigidStart ? StartKind::Rigid : StartKind::Intrinsic,
                         outcomes_[i].disagreement, [this, i] { return turning(i); }};
        };
        return replaces(score(k), score(than));
    }

    const Prepared& prepared_;
    const std::vector<FlowResult>& selection_flows_;
    const GuidedRounds& rounds_;
    const MatchOptions& options_;
    double diagonal_;
    const std::atomic<bool>& cancelled_;
    std::vector<Similarity> starts_;       // the rigid starts, then those added
    std::vector<std::size_t> contenders_;  // per outcome, its start
    std::vector<IntrinsicStart> intrinsic_;
    std::optional<AnalysedShapes> shapes_;  // once the second opinion needed them
    std::vector<GuidedMatch> outcomes_;
    std::vector<std::optional<double>> turning_agreements_;
    std::size_t kept_ = 0;
    CoarsestMatch match_;
};

// The steps of a rigid start's selection flow.
int selection_steps(const MatchOptions& options) {
    return std::min(options.starts.selection_iterations, options.max_iterations);
}

// The rigid starts' selection flows: `selection_iterations` steps each in the H1 metric, which
// lets the template reach the target's surface whatever the match's prior (the signatures are
// compared where the flow put the points).
std::vector<FlowResult> selection_flows(const Prepared& prepared, const LevelFlows& flows,
                                        const MatchOptions& options) {
    const std::vector<Similarity>& starts = prepared.starts;
    std::vector<FlowResult> results(starts.size());
    run_side_by_side(starts.size(), [&](std::size_t k) {
        results[k] =
            flows.flow(flows.coarsest(), placed_template(prepared.pyramid.back(), starts[k]),
                       selection_steps(options), starts[k], MatchPrior::H1, {}, 0, k == 0);
    });
    return results;
}

// The kept start flowed in the prior's metric, without guidance: the selection flow goes on
// (h1), or a flow from the start's placement.
FlowResult unguided_flow(const Prepared& prepared, const LevelFlows& flows,
                         const MatchOptions& options, const Similarity& start,
                         const FlowResult* selection) {
    if (selection == nullptr || options.prior != MatchPrior::H1) {
        return flows.flow(flows.coarsest(), placed_template(prepared.pyramid.back(), start),
                          options.max_iterations, start, options.prior);
    }
    FlowResult best = *selection;
    const int steps = selection_steps(options);
    if (best.status != FlowStatus::Converged && options.max_iterations > steps) {
        FlowResult more = flows.flow(flows.coarsest(), best.mesh, options.max_iterations - steps,
                                     start, options.prior);
        more.steps += best.steps;
        more.energy.insert(more.energy.begin(), best.energy.begin(), best.energy.end() - 1);
        best = std::move(more);
    }
    return best;
}

}  // namespace

CoarsestMatch match_coarsest_level(const Prepared& prepared, const LevelFlows& flows,
                                   const SpectralDescriptors* spectral, const MatchOptions& options,
                                   double diagonal, const std::atomic<bool>& cancelled,
                                   StageClock& clock) {
    // Of the selection flows within selection_tolerance of the lowest d_H, the one whose
    // signatures agree best goes on (MatchOptions::starts).
    std::vector<FlowResult> selection;
    std::size_t chosen = 0;
    if (prepared.starts.size() > 1) {
        selection = selection_flows(prepared, flows, options);
        chosen = choose_start(selection, *spectral, options.starts.selection_tolerance);
    }
    clock.end("start selection");
    if (cancelled && !selection.empty()) {
        return {.flow = std::move(selection[chosen]), .start = prepared.starts[chosen]};
    }
    if (!runs_guided_rounds(options)) {
        CoarsestMatch match{.flow = unguided_flow(prepared, flows, options, prepared.starts[chosen],
                                                  selection.empty() ? nullptr : &selection[chosen]),
                            .start = prepared.starts[chosen]};
        clock.end("coarsest flow");
        return match;
    }
    const GuidedRounds rounds(prepared.pyramid, flows, *spectral, options, diagonal, cancelled);
    Contest contest(prepared, selection, chosen, rounds, options, diagonal, cancelled);
    contest.run_contenders();
    clock.end("guided rounds");
    contest.ask_second_opinion();
    clock.end("second opinion");
    contest.try_alternative_starts();
    clock.end("alternative starts");
    contest.exchange_limbs();
    clock.end("limb swaps");
    CoarsestMatch match = contest.finish();
    if (guided_prior(options.prior) != options.prior && !cancelled) {
        // The kept result flows on in the prior's metric, at the stiffness it was kept at; the
        // level reports the plain d_H, as the guided rounds do.
        FlowResult prior_flow =
            flows.flow(flows.coarsest(), match.flow.mesh, options.max_iterations, match.start,
                       options.prior, {}, match.stretch_weight);
        prior_flow.steps += match.flow.steps;
        prior_flow.energy.front() = match.flow.energy.front();
        prior_flow.energy.back() =
            flows.distance_to_target(prepared.pyramid.back(), 1, {}).value(prior_flow.mesh);
        match.flow = std::move(prior_flow);
    }
    clock.end("prior flow");
    return match;
}

}  // namespace genflow::detail
