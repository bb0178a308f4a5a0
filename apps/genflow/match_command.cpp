// SPDX-License-Identifier: MIT
// genflow match TEMPLATE TARGET -o OUT: deform a template onto another pose of the same subject
// (genflow/matching/match.h) and report how close it got.
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>

#include "cli_support.h"
#include "commands.h"
#include "genflow/exceptions.h"
#include "genflow/io/mesh_format.h"
#include "genflow/io/read_part_model.h"
#include "match_job.h"

namespace genflow::cli {

namespace {

struct MatchCommandOptions {
    std::string template_path;
    std::string target_path;
    std::string output;
    std::string prior;  // empty: articulated with a part file, else h1
    std::string parts;
    std::string part_labels;
    std::string part_weights;
    std::string parts_pose;
    std::string correspondence;
    std::string frames;
    std::string summary;
    std::string ground_truth;
    MatchOptions match;
    bool no_align = false;
    bool no_turn_back = false;
    bool no_limb_swaps = false;
    bool no_signature_fallback = false;
    bool json = false;
    bool quiet = false;
};

void require_writable_format(const std::string& path) {
    const auto format = mesh_format_from_extension(path);
    if (!format || *format == MeshFormat::Stl) {
        throw IoError(path + ": cannot write this format (expected .obj, .ply or .off)");
    }
}

void run_match(const MatchCommandOptions& options) {
    require_writable_format(options.output);
    const LoadedMesh template_mesh = load_mesh(options.template_path);
    const LoadedMesh target = load_mesh(options.target_path);
    // The priors deform the template as a surface: it must be one.
    if (!template_mesh.report.manifold()) {
        throw IoError(options.template_path + ": the template is not manifold (" +
                      std::to_string(template_mesh.report.non_manifold_edges) + " edges, " +
                      std::to_string(template_mesh.report.non_manifold_vertices) +
                      " vertices); repair it first");
    }
    if (!options.json) {
        print_warnings(template_mesh);
        print_warnings(target);
    }
    MatchJob job;
    if (!options.ground_truth.empty()) {
        // Checked before the match, so that a wrong file costs nothing and writes nothing.
        const LoadedMesh truth = load_mesh(options.ground_truth);
        if (truth.mesh.V.rows() != template_mesh.mesh.V.rows()) {
            throw IoError(options.ground_truth + ": the ground truth has " +
                          std::to_string(truth.mesh.V.rows()) + " vertices, the template " +
                          std::to_string(template_mesh.mesh.V.rows()));
        }
        job.ground_truth = truth.mesh.V;
    }
    job.template_mesh = template_mesh.mesh;
    job.target = target.mesh;
    job.template_name = options.template_path;
    job.target_name = options.target_path;
    job.output = options.output;
    if (!options.correspondence.empty()) {
        job.correspondence = options.correspondence;
    }
    if (!options.frames.empty()) {
        job.frames = options.frames;
    }
    if (!options.summary.empty()) {
        job.summary = options.summary;
    }
    job.options = options.match;
    const std::string prior =
        !options.prior.empty() ? options.prior : (options.parts.empty() ? "h1" : "articulated");
    job.options.prior = *parse_match_prior(prior);
    if (!options.parts.empty()) {
        PartFiles files{options.parts, std::nullopt, std::nullopt, options.parts_pose};
        if (!options.part_labels.empty()) {
            files.labels = options.part_labels;
        }
        if (!options.part_weights.empty()) {
            files.weights = options.part_weights;
        }
        files.template_name = std::filesystem::path(options.template_path).stem().string();
        job.options.parts = read_part_model(files, template_mesh.mesh.V.rows());
    } else if (job.options.prior == MatchPrior::Articulated) {
        throw InvalidInput("match: --prior articulated needs --parts PARTS.json");
    }
    job.options.align = !options.no_align;
    job.options.turn_back_parts = !options.no_turn_back;
    job.options.swap_limbs = !options.no_limb_swaps;
    job.options.signature_fallback = !options.no_signature_fallback;
    job.progress_bar = !options.json && !options.quiet;
    const nlohmann::json summary = run_match_job(std::move(job));
    if (summary["doubtful"].get<bool>()) {
        std::cerr << "warning: " << options.target_path
                  << ": the match disagrees with the target's intrinsic shape (" << std::fixed
                  << std::setprecision(2) << summary["intrinsic_disagreement"].get<double>()
                  << ", above " << kDoubtfulDisagreement
                  << "): parts may sit on the wrong limb; check the result\n";
    }
    if (options.json) {
        std::cout << summary.dump(2) << '\n';
        return;
    }
    std::printf(
        "match: %s prior, %zu level(s), %.2f s (alignment %.2f s), %s; Hausdorff %.4g "
        "(%.3f%% of the target's diagonal), mean distance %.4g (%.3f%%); wrote %s\n",
        prior.c_str(), summary["levels"].size(), summary["seconds"].get<double>(),
        summary["alignment_seconds"].get<double>(),
        summary["converged"].get<bool>() ? "converged" : "not converged",
        summary["hausdorff"].get<double>(), 100 * summary["hausdorff_over_diagonal"].get<double>(),
        summary["mean_distance"].get<double>(),
        100 * summary["mean_distance_over_diagonal"].get<double>(), options.output.c_str());
    if (summary["second_opinion"].get<bool>()) {
        std::printf(
            "the second opinion, matched from an intrinsic start (the shapes' extremities), "
            "agreed with the target better than the rigid starts' result and was kept\n");
    }
    if (summary.contains("stranded_vertices")) {
        const auto& error = summary["correspondence_error_over_diagonal"];
        std::printf(
            "correspondence error against the ground truth: mean %.2f%%, median %.2f%%, max "
            "%.2f%% of its diagonal; %ld vertices stranded on the wrong part; %.2f%% of the "
            "area turned over\n",
            100 * error["mean"].get<double>(), 100 * error["median"].get<double>(),
            100 * error["max"].get<double>(), summary["stranded_vertices"].get<long>(),
            100 * summary["reversed_area"].get<double>());
    }
}

}  // namespace

void register_match_command(CLI::App& app) {
    auto options = std::make_shared<MatchCommandOptions>();
    auto* command = app.add_subcommand(
        "match",
        "Deform a template mesh onto a target (the same subject in another pose, any sampling "
        "and connectivity, any rigid motion and scale) by the flow of the pseudo-Hausdorff "
        "distance under a deformation prior; writes the deformed template");
    command->add_option("template", options->template_path, "Template mesh (moves)")->required();
    command->add_option("target", options->target_path, "Target mesh (fixed)")->required();
    command->add_option("-o,--output", options->output, "Deformed template (.obj, .ply, .off)")
        ->required();
    command
        ->add_option("--prior", options->prior,
                     "Deformation prior (the metric of the flow): l2 (baseline), h1 (smooth), "
                     "rigid (quasi-rigid: rigid motion and scaling preferred), articulated "
                     "(parts turn about their joints; needs --parts), isometric (bends "
                     "freely, resists local stretching). Default: articulated with --parts, "
                     "else h1")
        ->check(CLI::IsMember(match_prior_names()));
    command->add_option("--parts", options->parts,
                        "Part tree of the template (JSON; layouts in the README)");
    command->add_option("--part-labels", options->part_labels,
                        "Per-vertex part labels (one index per line), if the JSON names none");
    command->add_option("--part-weights", options->part_weights,
                        "Per-vertex part weights ('vertex part weight' lines), if the JSON "
                        "names none");
    command->add_option("--parts-pose", options->parts_pose,
                        "The pose of the part file the template is in (its joint centres "
                        "moved there; default: the pose the template's file name, or its last "
                        "'_'-separated word, names, else the rest pose)");
    command
        ->add_option("--levels", options->match.levels,
                     "Resolution levels (0: automatic, coarsest about 1000 vertices)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    command
        ->add_option("--iterations", options->match.max_iterations,
                     "Maximum flow steps on the coarsest level")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    command
        ->add_option("--fine-iterations", options->match.fine_iterations,
                     "Maximum flow steps on each finer level")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    command
        ->add_option(
            "--stagnation-tolerance", options->match.stagnation_tolerance,
            "A flow stops when its energy fell by less than this fraction over 20 steps "
            "(3e-3: 15-30 % faster at about the same mean error, but near-tied choices between "
            "starts then go either way)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    command
        ->add_option("--alpha", options->match.alpha, "Exponent of the pseudo-Hausdorff distance")
        ->check(CLI::Range(0.5, 1000.0))
        ->capture_default_str();
    command
        ->add_option("--coarse-epsilon", options->match.coarse_epsilon,
                     "Flow the first half of the coarsest level with an ε this many times "
                     "larger (a smoother distance; 1 = off)")
        ->check(CLI::Range(1.0, 100.0))
        ->capture_default_str();
    command
        ->add_option("--rigidity-length", options->match.isometric.rigidity_length,
                     "Isometric prior: patches smaller than this fraction of the diagonal keep "
                     "their edge lengths")
        ->check(CLI::Range(0.0, 10.0))
        ->capture_default_str();
    command
        ->add_option("--fake-edges", options->match.isometric.fake_edges,
                     "Isometric prior: edges added across the limbs for rigidity")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    command
        ->add_option("--candidates", options->match.alignment_candidates,
                     "Rigid starts flowed on the coarsest level; of those within 5 % of the "
                     "lowest d_H, the one whose heat kernel signatures agree best goes on")
        ->check(CLI::Range(1, 24))
        ->capture_default_str();
    command
        ->add_option("--contenders", options->match.contenders,
                     "Of those, the ones that agree within 25 % of the best go through the "
                     "guided flows each (at most this many); the one that ends agreeing best "
                     "is kept")
        ->check(CLI::Range(1, 24))
        ->capture_default_str();
    command
        ->add_option("--signature-guidance", options->match.signature_guidance,
                     "Weight of the heat kernel signatures in the coarsest flow, as a fraction "
                     "of the diagonal (points are near only if close and alike; 0 = off)")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    command
        ->add_option("--eigenfunction-guidance", options->match.eigenfunction_guidance,
                     "Weight of the Laplacian eigenfunctions, carried over by a functional map, "
                     "in a second guided coarsest flow that tells left from right (0 = off)")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    command
        ->add_option("--guidance-candidates", options->match.guidance_candidates,
                     "Run that second guided flow at the eigenfunction guidance times 1, 2, 4, "
                     "... and keep the result that agrees best with the target intrinsically")
        ->check(CLI::Range(1, 8))
        ->capture_default_str();
    command
        ->add_option("--stretch-weight", options->match.stretch_weight,
                     "Weight of the template's edge stretching (relative to its rest lengths, "
                     "times the diagonal) added to d_H in the last guided coarsest flow; it "
                     "keeps the template from sliding along the target (0 = off)")
        ->check(CLI::Range(0.0, 100.0))
        ->capture_default_str();
    command
        ->add_option("--stiffness-candidates", options->match.stiffness_candidates,
                     "Run that last flow at the stretch weight times 1, 4, 16, ... and keep the "
                     "result that agrees best with the target intrinsically (1 = the weight only)")
        ->check(CLI::Range(1, 8))
        ->capture_default_str();
    command
        ->add_option("--refinement-guidances", options->match.refinement_guidances,
                     "Refine the second coarsest level with flows guided by the eigenfunctions "
                     "at the eigenfunction guidance times 1, 1/2, ... (this many) and keep, of "
                     "those and the plain flow, the result that agrees best (0 = off)")
        ->check(CLI::Range(0, 8))
        ->capture_default_str();
    command
        ->add_option("--refinement-iterations", options->match.refinement_iterations,
                     "Steps of each guided refining flow")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    add_second_opinion_option(*command, options->match.second_opinion_above);
    command
        ->add_option("--alternative-starts", options->match.alternative_starts,
                     "A result still doubtful after the second opinion, or one the second "
                     "opinion gave, is matched again from the intrinsic starts of up to this "
                     "many further landmark sets, side by side; the one that disagrees least is "
                     "kept (0: none)")
        ->check(CLI::Range(0, 7))
        ->capture_default_str();
    command
        ->add_option("--alternative-starts-above", options->match.alternative_starts_above,
                     "Only a second opinion's result that disagrees more than this with the "
                     "target is matched again from the alternative starts (a doubtful one always "
                     "is; 0: every one; inf: none)")
        ->check(non_negative_or_infinity())
        ->capture_default_str();
    command->add_flag("--no-limb-swaps", options->no_limb_swaps,
                      "Do not check whether the match put two limbs on each other's places (a "
                      "left leg on the right one) by which way the extremities lie, nor match "
                      "again with them exchanged");
    command->add_flag("--no-signature-fallback", options->no_signature_fallback,
                      "Do not run a doubtful last coarsest round again guided by the heat kernel "
                      "signatures alone, whose result is kept if it disagrees less");
    command->add_flag("--no-turn-back", options->no_turn_back,
                      "Do not turn back the parts that a fine functional map (60 eigenfunctions) "
                      "places turned over in their own place (a hand palm for back) after the "
                      "refinement");
    command
        ->add_option("--map-fits", options->match.map_fits,
                     "At most this many fits of the refined match to where that map puts it, "
                     "each kept only if the heat kernel signatures then agree better with the "
                     "target, or the turning functions of pairs of extremities clearly better, "
                     "and not if the map was mirrored (0: none)")
        ->check(CLI::Range(0, 100))
        ->capture_default_str();
    command->add_flag("--implicit", options->match.implicit,
                      "Implicit flow steps (G + τA)⁻¹ dE/dX (paper eq. 11) instead of explicit");
    command->add_flag("--no-align", options->no_align,
                      "Skip the global rigid alignment (the inputs are already aligned)");
    command->add_option("--correspondence", options->correspondence,
                        "Write, per template vertex, the closest target face and barycentric "
                        "coordinates (text)");
    command->add_option("--frames", options->frames,
                        "Write every flow step as frame_NNNNN.ply into this directory "
                        "(coarse levels have their own vertex counts)");
    command->add_option("--summary", options->summary, "Write the JSON summary to this file");
    command->add_option(
        "--ground-truth", options->ground_truth,
        "The target's surface sampled as the template (same vertex count and order): report the "
        "correspondence error, the vertices stranded on the wrong part and the area turned over");
    command->add_flag("--json", options->json, "Print the JSON summary instead of text");
    command->add_flag("--quiet", options->quiet,
                      "No progress bar (it shows only on a terminal anyway)");
    command->callback([options] { run_match(*options); });
}

}  // namespace genflow::cli
