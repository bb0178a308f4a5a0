// SPDX-License-Identifier: MIT
#include "part_flags.h"

#include <filesystem>

#include "genflow/io/read_part_model.h"

namespace genflow::cli {

void add_part_flags(CLI::App& command, PartFlags& flags) {
    CLI::Option* tree = command.add_option(
        "--parts", flags.tree, "Part tree of the template (JSON; layouts in docs/matching.md)");
    // Labels or weights say which part a vertex is in: one of them, and only with a part tree.
    CLI::Option* labels =
        command.add_option("--part-labels", flags.labels,
                           "Per-vertex part labels (one index per line), if the JSON names none");
    command
        .add_option("--part-weights", flags.weights,
                    "Per-vertex part weights ('vertex part weight' lines), if the JSON "
                    "names none")
        ->excludes(labels)
        ->needs(tree);
    labels->needs(tree);
    command
        .add_option("--parts-pose", flags.pose,
                    "The pose of the part file the template is in (its joint centres "
                    "moved there; default: the pose the template's file name, or its last "
                    "'_'-separated word, names, else the rest pose)")
        ->needs(tree);
}

std::optional<PartModel> part_model(const PartFlags& flags, const std::string& template_path,
                                    Eigen::Index vertices) {
    if (flags.tree.empty()) {
        return std::nullopt;
    }
    PartFiles files{.tree = flags.tree,
                    .pose = flags.pose,
                    .template_name = std::filesystem::path(template_path).stem().string()};
    if (!flags.labels.empty()) {
        files.labels = flags.labels;
    }
    if (!flags.weights.empty()) {
        files.weights = flags.weights;
    }
    return read_part_model(files, vertices);
}

}  // namespace genflow::cli
