// SPDX-License-Identifier: MIT
#include "match_flags.h"

#include "cli_support.h"
#include "number_checks.h"

namespace genflow::cli {

void add_prior_flag(CLI::App& command, MatchFlags& flags) {
    command
        .add_option("--prior", flags.prior,
                    "Deformation prior (the metric of the flow): l2 (baseline), h1 (smooth), "
                    "rigid (quasi-rigid: rigid motion and scaling preferred), articulated "
                    "(parts turn about their joints; needs --parts), isometric (bends "
                    "freely, resists local stretching). Default: articulated with --parts, "
                    "else h1")
        ->check(CLI::IsMember(match_prior_names()));
}

void add_match_flags(CLI::App& command, MatchFlags& flags) {
    // Applied as soon as it is read, so that the other flags, applied after the whole line is
    // read, override it wherever they stand.
    command
        .add_option_function<std::string>(
            "--preset",
            [&flags](const std::string& preset) {
                flags.match = preset == "paper" ? paper_match_options() : MatchOptions{};
            },
            "Starting values of the options below: default, or paper (the paper's flow over "
            "the resolution levels alone, from the inputs' frames: no alignment, guidance, "
            "second opinions, fits or limb exchanges; the ablation's baseline)")
        ->check(CLI::IsMember({"default", "paper"}))
        ->trigger_on_parse();
    command
        .add_option("--levels", flags.match.levels,
                    "Resolution levels (0: automatic, coarsest about 1000 vertices)")
        ->check(non_negative_number())
        ->capture_default_str();
    command
        .add_option("--iterations", flags.match.max_iterations,
                    "Maximum flow steps on the coarsest level")
        ->check(non_negative_number())
        ->capture_default_str();
    command
        .add_option("--fine-iterations", flags.match.fine_iterations,
                    "Maximum flow steps on each finer level")
        ->check(non_negative_number())
        ->capture_default_str();
    command
        .add_option(
            "--stagnation-tolerance", flags.match.stagnation_tolerance,
            "A flow stops when its energy fell by less than this fraction over 20 steps "
            "(3e-3: 15-30 % faster at about the same mean error, but near-tied choices between "
            "starts then go either way)")
        ->check(non_negative_number())
        ->capture_default_str();
    command.add_option("--alpha", flags.match.alpha, "Exponent of the pseudo-Hausdorff distance")
        ->check(number_in(0.5, 1000.0))
        ->capture_default_str();
    command
        .add_option("--coarse-epsilon", flags.match.coarse_epsilon,
                    "Flow the first half of the coarsest level with an ε this many times "
                    "larger (a smoother distance; 1 = off)")
        ->check(number_in(1.0, 100.0))
        ->capture_default_str();
    command
        .add_option("--rigidity-length", flags.match.isometric.rigidity_length,
                    "Isometric prior: patches smaller than this fraction of the diagonal keep "
                    "their edge lengths")
        ->check(number_in(0.0, 10.0))
        ->capture_default_str();
    command
        .add_option("--fake-edges", flags.match.isometric.fake_edges,
                    "Isometric prior: edges added across the limbs for rigidity")
        ->check(number_in(0, 100000))
        ->capture_default_str();
    command
        .add_option("--candidates", flags.match.starts.candidates,
                    "Rigid starts flowed on the coarsest level; of those within 5 % of the "
                    "lowest d_H, the one whose heat kernel signatures agree best goes on")
        ->check(number_in(1, 24))
        ->capture_default_str();
    command
        .add_option("--signature-guidance", flags.match.guided.signature_guidance,
                    "Weight of the heat kernel signatures in the coarsest flow, as a fraction "
                    "of the diagonal (points are near only if close and alike; 0 = off)")
        ->check(number_in(0.0, 1.0))
        ->capture_default_str();
    command
        .add_option("--eigenfunction-guidance", flags.match.guided.eigenfunction_guidance,
                    "Weight of the Laplacian eigenfunctions, carried over by a functional map, "
                    "in a second guided coarsest flow that tells left from right (0 = off)")
        ->check(number_in(0.0, 1.0))
        ->capture_default_str();
    command
        .add_option("--guidance-candidates", flags.match.guided.guidance_candidates,
                    "Run that second guided flow at the eigenfunction guidance times 1, 2, 4, "
                    "... and keep the result that agrees best with the target intrinsically")
        ->check(number_in(1, 8))
        ->capture_default_str();
    command
        .add_option("--stretch-weight", flags.match.guided.stretch_weight,
                    "Weight of the template's edge stretching (relative to its rest lengths, "
                    "times the diagonal) added to d_H in the last guided coarsest flow; it "
                    "keeps the template from sliding along the target (0 = off)")
        ->check(number_in(0.0, 100.0))
        ->capture_default_str();
    command
        .add_option("--stiffness-candidates", flags.match.guided.stiffness_candidates,
                    "Run that last flow at the stretch weight times 1, 4, 16, ... and keep the "
                    "result that agrees best with the target intrinsically (1 = the weight only)")
        ->check(number_in(1, 8))
        ->capture_default_str();
    command
        .add_option("--refinement-guidances", flags.match.refinement.guidances,
                    "Refine the second coarsest level with flows guided by the eigenfunctions "
                    "at the eigenfunction guidance times 1, 1/2, ... (this many) and keep, of "
                    "those and the plain flow, the result that agrees best (0 = off)")
        ->check(number_in(0, 8))
        ->capture_default_str();
    command
        .add_option("--refinement-iterations", flags.match.refinement_iterations,
                    "Steps of each guided refining flow")
        ->check(number_in(0, 100000))
        ->capture_default_str();
    add_second_opinion_option(command, flags.match.second_opinion.above);
    command
        .add_option("--alternative-starts", flags.match.second_opinion.alternative_starts,
                    "A result still doubtful after the second opinion, or one the second "
                    "opinion gave, is matched again from the intrinsic starts of up to this "
                    "many further landmark sets, side by side; the one that disagrees least is "
                    "kept (0: none)")
        ->check(number_in(0, 7))
        ->capture_default_str();
    command
        .add_option("--alternative-starts-above",
                    flags.match.second_opinion.alternative_starts_above,
                    "A result that disagrees more than this with the target, from any start, "
                    "is matched again from the alternative starts (a doubtful one always is; 0: "
                    "every one; inf: only doubtful ones)")
        ->check(non_negative_or_infinity())
        ->capture_default_str();
    command.add_flag("--no-limb-swaps", flags.no_limb_swaps,
                     "Do not check whether the match put two limbs on each other's places (a "
                     "left leg on the right one) by which way the extremities lie, nor match "
                     "again with them exchanged");
    command.add_flag("--no-signature-fallback", flags.no_signature_fallback,
                     "Do not run a doubtful last coarsest round again guided by the heat kernel "
                     "signatures alone, whose result is kept if it disagrees less");
    command.add_flag("--no-signatures-reading", flags.no_signatures_reading,
                     "Do not make the match again with the eigenfunctions off (guided by the "
                     "heat kernel signatures alone), whose result is kept if its map commutes "
                     "better with the surfaces' Laplacians");
    command.add_flag("--report-orientation", flags.report_orientation,
                     "Report whether each reading's map keeps the surface's orientation (the "
                     "ratio above 1 where it reverses it; two eigen-solves of the whole meshes)");
    command
        .add_option("--landmark-weight", flags.match.landmarks.weight,
                    "Weight of the landmarks beside the distance (1: landmarks a diagonal off "
                    "weigh as surfaces a diagonal apart)")
        ->check(non_negative_number())
        ->capture_default_str();
    command.add_flag("--no-landmark-spread", flags.no_landmark_spread,
                     "Onto a partial target, do not spread the landmarks into a dense map of it by "
                     "the points' geodesic distances to them");
    command.add_flag("--no-counterparts", flags.no_counterparts,
                     "Give each template vertex as its counterpart (--correspondence) the "
                     "target's closest point to where the match put it, not the point near it "
                     "that the eigenfunctions agree with");
    command
        .add_option("--counterpart-reach", flags.match.counterparts.reach,
                    "How far, over the target's square root of area, a counterpart may be from "
                    "where the match put the vertex")
        ->check(number_in(1e-6, 10.0))
        ->capture_default_str();
    command.add_flag("--no-turn-back", flags.no_turn_back,
                     "Do not turn back the parts that a fine functional map (60 eigenfunctions) "
                     "places turned over in their own place (a hand palm for back) after the "
                     "refinement");
    command
        .add_option("--map-fits", flags.match.map_fit.max_fits,
                    "At most this many fits of the refined match to where that map puts it, "
                    "each kept only if the heat kernel signatures then agree better with the "
                    "target, or the turning functions of pairs of extremities clearly better, "
                    "and not if the map was mirrored (0: none)")
        ->check(number_in(0, 100))
        ->capture_default_str();
    CLI::Option* implicit =
        command.add_flag("--implicit", flags.match.implicit,
                         "Implicit flow steps (G + τA)⁻¹ dE/dX (paper eq. 11) instead of explicit");
    command
        .add_option("--quasi-newton", flags.match.quasi_newton_memory,
                    "Quasi-Newton flow steps: L-BFGS in the prior's metric with this many past "
                    "steps (0: steepest descent)")
        ->check(number_in(0, 100))
        ->excludes(implicit)
        ->capture_default_str();
    command
        .add_option("--first-step", flags.first_step,
                    "Where each flow step's backtracking starts: doubling (twice the last step's "
                    "τ, or that τ after a step that backtracked) or last-decrease (where the "
                    "quadratic that predicts the last step's decrease has its minimum: about one "
                    "distance evaluation a step instead of 1.5)")
        ->check(CLI::IsMember({"last-decrease", "doubling"}))
        ->capture_default_str();
    command
        .add_option("--target-extent", flags.target_extent,
                    "How much of the template the target shows: partial (a single view, large "
                    "holes, a limb cut off: matched by the one-sided distance, at the template's "
                    "scale, without the intrinsic stages), complete, or auto (partial if its "
                    "boundary is long for its area)")
        ->check(CLI::IsMember({"auto", "complete", "partial"}))
        ->capture_default_str();
    command.add_flag("--no-align", flags.no_align,
                     "Skip the global rigid alignment (the inputs are already aligned)");
}

MatchOptions resolved(const MatchFlags& flags, bool has_parts) {
    MatchOptions options = flags.match;
    const std::string prior =
        !flags.prior.empty() ? flags.prior : (has_parts ? "articulated" : "h1");
    options.prior = *parse_match_prior(prior);
    options.first_step =
        flags.first_step == "last-decrease" ? FirstStep::LastDecrease : FirstStep::Doubling;
    options.starts.enabled = options.starts.enabled && !flags.no_align;
    options.turn_back.enabled = options.turn_back.enabled && !flags.no_turn_back;
    options.counterparts.enabled = options.counterparts.enabled && !flags.no_counterparts;
    options.limb_swaps.enabled = options.limb_swaps.enabled && !flags.no_limb_swaps;
    options.landmarks.spread_onto_partial =
        options.landmarks.spread_onto_partial && !flags.no_landmark_spread;
    options.guided.signature_fallback =
        options.guided.signature_fallback && !flags.no_signature_fallback;
    options.signatures_reading.enabled =
        options.signatures_reading.enabled && !flags.no_signatures_reading;
    options.signatures_reading.report_orientation =
        options.signatures_reading.report_orientation || flags.report_orientation;
    options.partial.extent = *parse_target_extent(flags.target_extent);
    return options;
}

}  // namespace genflow::cli
