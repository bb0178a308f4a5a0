// SPDX-License-Identifier: MIT
// genflow batch TEMPLATE --targets LIST|DIR --output-dir D [--shard i/N] [--resume]: one
// template matched onto many targets, each as `genflow match` would, a failed target recorded
// and the batch going on; one line per target in D's JSONL record.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "cli_support.h"
#include "commands.h"
#include "genflow/exceptions.h"
#include "genflow/io/atomic_file.h"
#include "genflow/io/read_file.h"
#include "genflow/io/read_mesh.h"
#include "genflow/io/read_points.h"
#include "genflow/version.h"
#include "match_flags.h"
#include "match_job.h"
#include "part_flags.h"
#include "reports.h"
#include "shard.h"

namespace genflow::cli {

namespace {

struct BatchOptions {
    std::string template_path;
    std::string targets;  // a directory of meshes, or a text file naming one per line
    std::string output_dir;
    std::string shard;
    bool resume = false;
    MatchFlags flags;
    PartFlags parts;
};

// A target and the name its outputs go by (its file name without the extension).
struct Target {
    std::filesystem::path path;
    std::string name;
};

bool is_target_file(const std::filesystem::path& path) {
    return mesh_format_from_extension(path).has_value() || is_xyz_file(path);
}

// The mesh and point files of `directory`, by name.
std::vector<std::filesystem::path> files_in(const std::filesystem::path& directory) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(directory)) {
        if (entry.is_regular_file() && is_target_file(entry.path())) {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

// The paths a list file names, one per line (relative ones from the list's directory; blank
// lines and '#' comments skipped).
std::vector<std::filesystem::path> files_listed(const std::filesystem::path& list) {
    std::vector<std::filesystem::path> files;
    const std::string text = read_file(list);
    std::size_t line_number = 0;
    for (std::size_t start = 0; start < text.size();) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        std::string line = text.substr(start, end - start);
        start = end + 1;
        ++line_number;
        line = line.substr(0, line.find('#'));
        line.erase(line.find_last_not_of(" \t\r") + 1);
        line.erase(0, line.find_first_not_of(" \t"));
        if (line.empty()) {
            continue;
        }
        const std::filesystem::path path = list.parent_path() / line;
        if (!is_target_file(path)) {
            throw IoError(list.string() + ": line " + std::to_string(line_number) + ": '" +
                          printable(line) + "' is not a mesh or point file");
        }
        files.push_back(path);
    }
    return files;
}

// Every target, checked before any work: names unique (their outputs would overwrite each
// other), at least one.
std::vector<Target> targets_of(const std::string& given) {
    const std::filesystem::path path(given);
    if (!std::filesystem::exists(path)) {
        throw IoError(given + ": no such directory or list file");
    }
    const std::vector<std::filesystem::path> files =
        std::filesystem::is_directory(path) ? files_in(path) : files_listed(path);
    std::vector<Target> targets;
    std::set<std::string> names;
    for (const std::filesystem::path& file : files) {
        const std::string name = file.stem().string();
        if (!names.insert(name).second) {
            throw IoError(given + ": two targets are named \"" + printable(name) +
                          "\" (their outputs would overwrite each other)");
        }
        targets.push_back({file, name});
    }
    if (targets.empty()) {
        throw IoError(given + ": no target (.obj, .ply, .off, .stl or .xyz files)");
    }
    return targets;
}

// The outputs of target `name` in the output directory.
struct TargetOutputs {
    std::filesystem::path mesh;
    std::filesystem::path correspondence;
    std::filesystem::path summary;
};

TargetOutputs outputs_of(const std::filesystem::path& directory, const std::string& name) {
    return {directory / (name + ".ply"), directory / (name + ".correspondence.txt"),
            directory / (name + ".json")};
}

// Whether an earlier run finished this target: all its outputs there (they are written all or
// none, so their presence means complete) and its summary readable.
bool finished_before(const TargetOutputs& outputs) {
    if (!std::filesystem::exists(outputs.mesh) ||
        !std::filesystem::exists(outputs.correspondence) ||
        !std::filesystem::exists(outputs.summary)) {
        return false;
    }
    try {
        return nlohmann::json::parse(read_file(outputs.summary)).is_object();
    } catch (const std::exception&) {
        return false;
    }
}

// The template, loaded once, its part model, and its analyses, kept from the first target on.
struct BatchTemplate {
    LoadedMesh loaded;
    std::optional<PartModel> parts;
    std::shared_ptr<TemplateCache> cache = std::make_shared<TemplateCache>();
};

// The template and its part model, checked before any work.
BatchTemplate batch_template_of(const BatchOptions& options) {
    BatchTemplate batch_template;
    batch_template.loaded = load_mesh(options.template_path);
    batch_template.parts =
        part_model(options.parts, options.template_path, batch_template.loaded.mesh.V.rows());
    if (!batch_template.parts && resolved(options.flags, false).prior == MatchPrior::Articulated) {
        throw InvalidInput("batch: --prior articulated needs --parts PARTS.json");
    }
    return batch_template;
}

// One target matched as `genflow match` would; its record.
nlohmann::json match_target(const BatchOptions& options, const BatchTemplate& batch_template,
                            const Target& target, const TargetOutputs& outputs) {
    MatchJob job = match_job_for(batch_template.loaded, load_target(target.path), true);
    job.output = outputs.mesh;
    job.correspondence = outputs.correspondence;
    job.summary = outputs.summary;
    job.options = resolved(options.flags, batch_template.parts.has_value());
    job.options.parts = batch_template.parts;
    job.options.template_cache = batch_template.cache;
    const nlohmann::json summary = run_match_job(std::move(job));
    return {{"status", "matched"},
            {"seconds", summary["seconds"]},
            {"hausdorff_over_diagonal", summary["hausdorff_over_diagonal"]},
            {"mean_distance_over_diagonal", summary["mean_distance_over_diagonal"]}};
}

// A target's record: matched, found complete from an earlier run, or failed with why.
nlohmann::json run_target(const BatchOptions& options, const BatchTemplate& batch_template,
                          const Target& target) {
    const TargetOutputs outputs = outputs_of(options.output_dir, target.name);
    nlohmann::json record;
    if (options.resume && finished_before(outputs)) {
        record = {{"status", "done before"}};
    } else {
        try {
            record = match_target(options, batch_template, target, outputs);
        } catch (const std::exception& error) {
            // InvalidInput, IoError, SolverError, bad_alloc: recorded, and the batch goes on.
            record = {{"status", "failed"}, {"error", printable(error.what())}};
        }
    }
    record["target"] = target.path.string();
    record["name"] = target.name;
    record["outputs"] = {{"mesh", outputs.mesh.string()},
                         {"correspondence", outputs.correspondence.string()},
                         {"summary", outputs.summary.string()}};
    record["genflow"] = std::string(kVersion);
    record["command_line"] = command_line();  // every option, as given
    return record;
}

// The record's file: batch.jsonl, or batch.i-of-N.jsonl for a shard (shards running at once
// never write the same file).
std::filesystem::path record_path(const BatchOptions& options) {
    if (options.shard.empty()) {
        return std::filesystem::path(options.output_dir) / "batch.jsonl";
    }
    const Shard share = parse_shard(options.shard);
    return std::filesystem::path(options.output_dir) /
           ("batch." + std::to_string(share.index) + "-of-" + std::to_string(share.count) +
            ".jsonl");
}

// The number of targets that failed.
int run_batch(const BatchOptions& options) {
    const std::vector<Target> share = shard_of(targets_of(options.targets), options.shard);
    const BatchTemplate batch_template = batch_template_of(options);
    create_output_directory(options.output_dir);
    const std::filesystem::path records = record_path(options);
    check_output_path(records);
    print_warnings(batch_template.loaded);
    std::string lines;
    int failed = 0;
    for (std::size_t t = 0; t < share.size(); ++t) {
        const nlohmann::json record = run_target(options, batch_template, share[t]);
        failed += record["status"] == "failed" ? 1 : 0;
        std::printf("batch: %zu/%zu %s: %s\n", t + 1, share.size(),
                    printable(share[t].name).c_str(), record["status"].get<std::string>().c_str());
        std::fflush(stdout);
        lines += record.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
        write_file_atomically(records, lines);  // after every target: a killed run keeps its record
    }
    std::printf("batch: %zu targets, %d failed; record %s\n", share.size(), failed,
                printable(records.string()).c_str());
    return failed;
}

}  // namespace

void register_batch_command(CLI::App& app) {
    auto options = std::make_shared<BatchOptions>();
    auto* command = app.add_subcommand(
        "batch",
        "Match one template onto many targets, each as genflow match would: per target its "
        "deformed template, correspondence and summary, and one line in a JSONL record; a "
        "failed target is recorded and the batch goes on (exit code 1 if any failed)");
    command->add_option("template", options->template_path, "The template mesh")->required();
    command
        ->add_option("--targets", options->targets,
                     "A directory of targets (.obj, .ply, .off, .stl, .xyz), or a text file "
                     "naming one per line")
        ->required();
    command
        ->add_option("--output-dir", options->output_dir,
                     "Where NAME.ply, NAME.correspondence.txt and NAME.json go, NAME each "
                     "target's file name without its extension, with batch.jsonl")
        ->required();
    command->add_option("--shard", options->shard,
                        "i/N: every N-th target from the i-th (job arrays; the record is then "
                        "batch.i-of-N.jsonl)");
    command->add_flag("--resume", options->resume,
                      "Skip the targets whose outputs an earlier run finished");
    add_part_flags(*command, options->parts);
    add_prior_flag(*command, options->flags);
    add_match_flags(*command, options->flags);
    command->callback([options] {
        if (run_batch(*options) > 0) {
            throw SomeWorkFailed{};
        }
    });
}

}  // namespace genflow::cli
