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
#include "genflow/io/atomic_file.h"
#include "genflow/io/read_landmarks.h"
#include "match_flags.h"
#include "match_job.h"
#include "number_checks.h"
#include "part_flags.h"
#include "reports.h"

namespace genflow::cli {

namespace {

struct MatchCommandOptions {
    std::string template_path;
    std::string target_path;
    std::string output;
    PartFlags parts;
    std::string correspondence;
    std::string frames;
    int frame_every = 1;
    std::string summary;
    std::string colored;
    std::string report;
    std::string ground_truth;
    std::string landmarks;
    MatchFlags flags;
    bool json = false;
    bool quiet = false;
};

// The priors deform the template as a surface, so match() matches meshes as they come as
// repair_surface() makes them: say what it did.
void print_repairs(const std::string& path, const std::string& repairs) {
    if (!repairs.empty()) {
        std::cerr << "warning: " << printable(path) << ": matched as repaired (" << repairs
                  << "); the output keeps every vertex\n";
    }
}

void print_point_cloud(const LoadedMesh& target) {
    if (target.points == 0) {
        return;
    }
    std::cerr << "note: " << printable(target.path.string()) << ": a point cloud of "
              << target.points << " points" << (target.normals ? " with normals" : "")
              << ", matched on a surface of " << target.mesh.F.rows() << " triangles on them\n";
    if (!target.normals) {
        std::cerr << "warning: " << printable(target.path.string())
                  << ": no normals: where two sheets face each other closer than the points' "
                     "spacing (an arm against the torso), the surface may bridge them; give "
                     "'x y z nx ny nz' lines (or a PLY's nx ny nz) where the scanner has normals\n";
    }
}

void run_match(const MatchCommandOptions& options) {
    check_mesh_output(options.output);
    if (!options.colored.empty()) {
        check_mesh_output(options.colored);
    }
    if (!options.report.empty()) {
        check_report_output(options.report);
    }
    // Every output checked before any work, so that a typo costs nothing.
    for (const std::string& output : {options.output, options.correspondence, options.summary}) {
        if (!output.empty()) {
            check_output_path(output);
        }
    }
    const LoadedMesh template_mesh = load_mesh(options.template_path);
    const LoadedMesh target = load_target(options.target_path);
    if (!options.json) {
        print_warnings(template_mesh);
        print_warnings(target);
        print_point_cloud(target);
    }
    const bool quiet = options.json || options.quiet;
    MatchJob job = match_job_for(template_mesh, target, quiet);
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
    job.output = options.output;
    if (!options.correspondence.empty()) {
        job.correspondence = options.correspondence;
    }
    if (!options.frames.empty()) {
        job.frames = options.frames;
        job.frame_every = options.frame_every;
    }
    if (!options.summary.empty()) {
        job.summary = options.summary;
    }
    if (!options.colored.empty()) {
        job.colored = options.colored;
    }
    if (!options.report.empty()) {
        job.report = options.report;
    }
    job.options = resolved(options.flags, !options.parts.tree.empty());
    const std::string prior = to_string(job.options.prior);
    job.options.parts =
        part_model(options.parts, options.template_path, template_mesh.mesh.V.rows());
    if (!job.options.parts && job.options.prior == MatchPrior::Articulated) {
        throw InvalidInput("match: --prior articulated needs --parts PARTS.json");
    }
    if (!options.landmarks.empty()) {
        job.options.landmarks.points =
            read_landmarks(options.landmarks, template_mesh.mesh.V.rows(), target.mesh);
    }
    const bool extent_automatic = job.options.partial.extent == TargetExtent::Automatic;
    const nlohmann::json summary = run_match_job(std::move(job));
    if (!options.json) {
        print_repairs(options.template_path, summary["template_repairs"].get<std::string>());
        if (target.points == 0) {  // a point cloud's surface is genflow's, repairs and all
            print_repairs(options.target_path, summary["target_repairs"].get<std::string>());
        }
    }
    if (summary["partial_target"].get<bool>() && extent_automatic && !options.json) {
        std::cerr << "note: " << printable(options.target_path)
                  << ": shows only part of the template (its boundary is long for its area): "
                     "matched by the one-sided distance, at the template's scale, without the "
                     "intrinsic stages; --target-extent complete matches it as a whole\n";
    }
    if (summary["doubtful"].get<bool>()) {
        std::cerr << "warning: " << printable(options.target_path)
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
        100 * summary["mean_distance_over_diagonal"].get<double>(),
        printable(options.output).c_str());
    if (summary.contains("colored")) {
        const nlohmann::json& colored = summary["colored"];
        std::printf(
            "%s: coloured by its %s per vertex on viridis, from 0 (dark purple) to %.4g "
            "(yellow)\n",
            printable(options.colored).c_str(), colored["property"].get<std::string>().c_str(),
            colored["scale"][1].get<double>());
    }
    if (!options.report.empty()) {
        std::printf("%s: the match to look at in a browser\n", printable(options.report).c_str());
    }
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
    command
        ->add_option(
            "target", options->target_path,
            "Target mesh (fixed), or a point cloud: an .xyz file or a mesh file without faces")
        ->required();
    command->add_option("-o,--output", options->output, "Deformed template (.obj, .ply, .off)")
        ->required();
    add_part_flags(*command, options->parts);
    command->add_option("--landmarks", options->landmarks,
                        "Known correspondences, one per line: 'i x y z' (template vertex i goes "
                        "to the point) or 'i j' (to target vertex j), 0-based, each with an "
                        "optional weight last, '#' comments");
    add_prior_flag(*command, options->flags);
    add_match_flags(*command, options->flags);
    command->add_option("--correspondence", options->correspondence,
                        "Write, per template vertex, the closest target face and barycentric "
                        "coordinates (text)");
    command->add_option("--frames", options->frames,
                        "Write the template as every flow step deformed it, at its own "
                        "resolution (coarse levels' motion carried to it), as frame_NNNNN.ply "
                        "into this directory, or as one animated glTF to a name ending in .glb");
    command->add_option("--frame-every", options->frame_every, "Every k-th step only, for --frames")
        ->check(positive_number());
    command->add_option("--summary", options->summary, "Write the JSON summary to this file");
    command->add_option("--colored", options->colored,
                        "Write the deformed template coloured per vertex on viridis by its error "
                        "(with --ground-truth) or its distance to the target (.ply, .obj, .off)");
    command->add_option("--report", options->report,
                        "Write an HTML page showing the match: the meshes in a 3D view (coloured "
                        "by distance or error), d_H per step of each level, the summary (.html)");
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
