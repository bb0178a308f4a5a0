// SPDX-License-Identifier: MIT
// genflow eval PAIRS.json: runs the matcher over every pair of a pairs.json (the format of
// $GENFLOW_DATA/pairs.json) with each prior and prints the correspondence error against the
// ground truth as a Markdown table (or JSON).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.h"
#include "commands.h"
#include "genflow/exceptions.h"
#include "genflow/io/read_file.h"
#include "genflow/io/read_mesh.h"
#include "genflow/io/read_part_model.h"
#include "genflow/io/write_mesh.h"
#include "genflow/matching/correspondence_error.h"
#include "genflow/matching/match.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/spatial/surface_distance.h"
#include "match_flags.h"

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

nlohmann::json read_pairs(const std::filesystem::path& path) {
    const std::string text = read_file(path);
    try {
        nlohmann::json pairs = nlohmann::json::parse(text);
        if (!pairs.is_array()) {
            throw IoError(path.string() + ": expected a JSON array of pairs");
        }
        return pairs;
    } catch (const nlohmann::json::exception& e) {
        throw IoError(path.string() + ": not valid JSON (" + e.what() + ")");
    }
}

std::string field(const std::filesystem::path& file, const nlohmann::json& pair, const char* key) {
    if (!pair.contains(key) || !pair[key].is_string()) {
        throw IoError(file.string() + ": a pair lacks the string \"" + key + "\"");
    }
    return pair[key].get<std::string>();
}

// A pair's name, which names its files in --output-dir: a plain file name, so that no pairs
// file can write outside that directory (no "..", no separator, not absolute, not hidden).
std::string output_name(const std::filesystem::path& file, const std::string& name) {
    if (name.empty() || name.front() == '.' || name.find('/') != std::string::npos ||
        name.find('\0') != std::string::npos) {
        throw IoError(file.string() +
                      ": a pair's name must be a plain file name (no '/', not "
                      "starting with '.'), got \"" +
                      name + "\"");
    }
    return name;
}

// The pair's target: its "target_remeshed" file, or else the ground truth simplified to the
// share "target_simplified" of its vertices (quadric collapses onto kept vertices: another
// sampling and connectivity than the template's, on the same surface), so that any two poses
// of a subject make a pair without a remesher.
TriangleMesh target_of(const std::filesystem::path& file, const std::filesystem::path& base,
                       const std::string& name, const nlohmann::json& pair,
                       const TriangleMesh& truth) {
    if (pair.contains("target_remeshed")) {
        return read_mesh(base / field(file, pair, "target_remeshed"));
    }
    const auto share = pair.find("target_simplified");
    if (share == pair.end()) {
        throw IoError(file.string() + ": pair " + name +
                      " has neither \"target_remeshed\" nor \"target_simplified\"");
    }
    if (!share->is_number() || !(share->get<double>() > 0 && share->get<double>() <= 1)) {
        throw IoError(file.string() + ": pair " + name +
                      ": \"target_simplified\" must be a share of the vertices in (0, 1]");
    }
    return coarsen_to_share(truth, share->get<double>()).mesh;
}

// The mean distance of a stage's vertices from where the ground truth has them.
double stage_error(const MatchStage& stage, const TriangleMesh& truth) {
    const Eigen::MatrixX3d& V = stage.mesh->V;
    double sum = 0;
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
        sum +=
            (V.row(v) - truth.V.row((*stage.template_vertex)[static_cast<std::size_t>(v)])).norm();
    }
    return V.rows() > 0 ? sum / static_cast<double>(V.rows()) : 0;
}

void run_eval(const EvalOptions& options) {
    const std::filesystem::path file(options.pairs);
    const nlohmann::json pairs = read_pairs(file);
    const std::filesystem::path base =
        options.data_dir.empty() ? file.parent_path() : std::filesystem::path(options.data_dir);
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
    for (const auto& pair : pairs) {
        const std::string name = output_name(file, field(file, pair, "name"));
        if (!options.only.empty() &&
            std::find(options.only.begin(), options.only.end(), name) == options.only.end()) {
            continue;
        }
        const TriangleMesh template_mesh = read_mesh(base / field(file, pair, "template"));
        const TriangleMesh truth = read_mesh(base / field(file, pair, "target_ground_truth"));
        const TriangleMesh target = target_of(file, base, name, pair, truth);
        if (truth.V.rows() != template_mesh.V.rows()) {
            throw IoError(file.string() + ": pair " + name +
                          ": the ground truth has another vertex count than the template");
        }
        std::optional<PartModel> parts;
        if (pair.contains("template_parts")) {  // optional: for the articulated prior
            PartFiles files{base / field(file, pair, "template_parts")};
            files.template_name =
                std::filesystem::path(field(file, pair, "template")).stem().string();
            if (pair.contains("template_parts_pose")) {
                files.pose = field(file, pair, "template_parts_pose");
            }
            if (pair.contains("template_part_labels")) {
                files.labels = base / field(file, pair, "template_part_labels");
            }
            if (pair.contains("template_part_weights")) {
                files.weights = base / field(file, pair, "template_part_weights");
            }
            parts = read_part_model(files, template_mesh.V.rows());
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
                match_options.stages = [&](const MatchStage& stage) {
                    stages.push_back({{"level", stage.level},
                                      {"stage", std::string(stage.stage)},
                                      {"vertices", stage.mesh->V.rows()},
                                      {"mean", stage_error(stage, truth) / diagonal}});
                };
            }
            const MatchResult result = match(template_mesh, target, match_options);
            const CorrespondenceError error = correspondence_error(result.deformed.V, truth);
            const double hausdorff =
                surface_distances(result.deformed, target).hausdorff / diagonal;
            if (!output_dir.empty()) {
                write_mesh(output_dir / (name + "." + prior_name + ".ply"), result.deformed);
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
                        "faces)");
    command->add_flag("--stages", options->stages,
                      "Also the mean error after each stage of each level (\"stages\" in the "
                      "JSON; on standard error beside the table): where a match lost accuracy");
    command->add_flag("--json", options->json, "Print JSON instead of a table");
    command->callback([options] { run_eval(*options); });
}

}  // namespace genflow::cli
