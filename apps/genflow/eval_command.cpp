// SPDX-License-Identifier: MIT
// genflow eval PAIRS.json: runs the matcher over every pair of a pairs.json (the format of
// $GENFLOW_DATA/pairs.json) with each prior and prints the correspondence error against the
// ground truth as a Markdown table (or JSON).
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_support.h"
#include "commands.h"
#include "genflow/exceptions.h"
#include "genflow/io/read_mesh.h"
#include "genflow/io/read_part_model.h"
#include "genflow/io/write_mesh.h"
#include "genflow/matching/correspondence_error.h"
#include "genflow/matching/match.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/spatial/surface_distance.h"
#include "match_flags.h"
#include "pairs_file.h"

namespace genflow::cli {

namespace {

struct EvalOptions {
    std::string pairs;
    std::vector<std::string> priors{"h1", "rigid", "articulated"};
    std::vector<std::string> only;  // pair names; empty: all
    std::string data_dir;           // paths in the pairs are relative to it (default: the file's)
    MatchFlags flags;               // the algorithm's options (the priors come from `priors`)
    std::string output_dir;         // where the targets matched and the results go; empty: nowhere
    bool stages = false;            // the mean error after each stage of each level too
    bool json = false;
};

// The pair's target: its "target_remeshed" file, or else the ground truth simplified to the
// share "target_simplified" of its vertices (quadric collapses onto kept vertices: another
// sampling and connectivity than the template's, on the same surface), so that any two poses
// of a subject make a pair without a remesher.
TriangleMesh target_of(const EvalPair& pair, const TriangleMesh& truth) {
    if (pair.target_remeshed) {
        return read_mesh(*pair.target_remeshed);
    }
    return coarsen_to_share(truth, pair.target_simplified).mesh;
}

void run_eval(const EvalOptions& options) {
    const std::filesystem::path file(options.pairs);
    const std::filesystem::path base =
        options.data_dir.empty() ? file.parent_path() : std::filesystem::path(options.data_dir);
    const std::vector<EvalPair> pairs = read_pairs_file(file, base, options.only);
    nlohmann::json rows = nlohmann::json::array();
    const std::filesystem::path output_dir(options.output_dir);
    if (!output_dir.empty()) {
        create_output_directory(output_dir);
    }
    if (!options.json) {
        std::printf(
            "| pair | prior | mean error | median | max | stranded | reversed | Hausdorff | time "
            "|\n"
            "|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
    }
    for (const EvalPair& pair : pairs) {
        const std::string& name = pair.name;
        const TriangleMesh template_mesh = read_mesh(pair.template_mesh);
        const TriangleMesh truth = read_mesh(pair.ground_truth);
        const TriangleMesh target = target_of(pair, truth);
        if (truth.V.rows() != template_mesh.V.rows()) {
            throw IoError(file.string() + ": pair " + name +
                          ": the ground truth has another vertex count than the template");
        }
        std::optional<PartModel> parts;
        if (pair.parts) {  // optional: for the articulated prior
            parts = read_part_model(*pair.parts, template_mesh.V.rows());
        }
        const double diagonal = bounding_box_diagonal(truth);
        // The target as matched (a simplified one exists nowhere else), to look at the results
        // against.
        if (!output_dir.empty()) {
            write_mesh(output_dir / (name + ".target.ply"), target);
        }
        for (const std::string& prior_name : options.priors) {
            const MatchPrior prior = *parse_match_prior(prior_name);
            if (prior == MatchPrior::Articulated && !parts) {
                continue;
            }
            MatchOptions match_options = resolved(options.flags, parts.has_value());
            match_options.prior = prior;
            match_options.parts = parts;
            nlohmann::json stages = nlohmann::json::array();
            if (options.stages) {
                match_options.stages = stage_errors(template_mesh, truth.V, diagonal, stages);
            }
            const MatchResult result = match(template_mesh, target, match_options);
            const CorrespondenceError error = correspondence_error(result.deformed.V, truth);
            const double hausdorff =
                surface_distances(result.deformed, target).hausdorff / diagonal;
            if (!output_dir.empty()) {
                VertexAttributes values;
                values.scalars = result_values(result.deformed, target, &truth.V);
                write_mesh(output_dir / (name + "." + prior_name + ".ply"), result.deformed,
                           values);
            }
            nlohmann::json row = {{"pair", name},
                                  {"prior", prior_name},
                                  {"mean", error.mean},
                                  {"median", error.median},
                                  {"max", error.max},
                                  {"stranded_vertices", error.stranded_count},
                                  {"reversed_area", error.reversed_area},
                                  {"hausdorff", hausdorff},
                                  {"seconds", result.seconds}};
            row.update(match_choices(result));
            if (options.stages) {
                row["stages"] = stages;
                if (!options.json) {  // beside the table, which stays Markdown
                    std::string line = name + " " + prior_name + ":";
                    for (const nlohmann::json& stage : stages) {
                        char figure[32];
                        std::snprintf(figure, sizeof figure, " %.2f %%",
                                      100 * stage["mean"].get<double>());
                        line += " level " + std::to_string(stage["level"].get<int>()) + " " +
                                stage["stage"].get<std::string>() + figure + ",";
                    }
                    line.back() = '\n';
                    std::fputs(line.c_str(), stderr);
                }
            }
            rows.push_back(row);
            if (!options.json) {
                std::printf(
                    "| %s | %s | %.2f %% | %.2f %% | %.2f %% | %ld | %.2f %% | %.2f %% | %.1f s "
                    "|\n",
                    name.c_str(), prior_name.c_str(), 100 * error.mean, 100 * error.median,
                    100 * error.max, static_cast<long>(error.stranded_count),
                    100 * error.reversed_area, 100 * hausdorff, result.seconds);
                std::fflush(stdout);
            }
        }
    }
    if (options.json) {
        std::cout << rows.dump(2) << '\n';
    } else {
        std::printf(
            "\nErrors are |x_i − ground truth_i| over the ground-truth target's bounding-box "
            "diagonal; stranded: how many template vertices were put on the wrong part of the "
            "shape (the ground-truth point nearest to where a vertex was put is more than 10 %% "
            "of the diagonal from where it belongs along the surface, and more than twice as "
            "far as straight; one within a mean edge length of where it belongs is at its "
            "place); reversed: the share of the ground truth's area whose faces the "
            "match turned over (a part put back to front); Hausdorff is the exact symmetric "
            "distance to the remeshed target over the same diagonal.\n");
    }
}

}  // namespace

void register_eval_command(CLI::App& app) {
    auto options = std::make_shared<EvalOptions>();
    auto* command = app.add_subcommand(
        "eval",
        "Match every pair of a pairs.json (template, remeshed target, ground-truth target) "
        "with each prior and print the correspondence error against the ground truth; a pair "
        "may give \"target_simplified\": SHARE instead of a remeshed target, to match the "
        "ground truth simplified to that share of its vertices");
    command->add_option("pairs", options->pairs, "pairs.json (the format of $GENFLOW_DATA)")
        ->required();
    command
        ->add_option("--priors", options->priors, "Priors to run (articulated: pairs with parts)")
        ->delimiter(',')
        ->check(CLI::IsMember(match_prior_names()))
        ->capture_default_str();
    command->add_option("--pairs", options->only, "Only these pairs (names)")->delimiter(',');
    command->add_option("--data-dir", options->data_dir,
                        "Directory the paths in the file are relative to (default: the file's)");
    add_match_flags(*command, options->flags);
    command->add_option("--output-dir", options->output_dir,
                        "Write there each pair's target as matched (NAME.target.ply) and each "
                        "match's deformed template (NAME.PRIOR.ply, the template's vertices and "
                        "faces, with each vertex's distance to the target and error)");
    command->add_flag("--stages", options->stages,
                      "Also the mean error after each stage of each level (\"stages\" in the "
                      "JSON; on standard error beside the table): where a match lost accuracy");
    command->add_flag("--json", options->json, "Print JSON instead of a table");
    command->callback([options] { run_eval(*options); });
}

}  // namespace genflow::cli
