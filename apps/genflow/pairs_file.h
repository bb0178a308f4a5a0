// SPDX-License-Identifier: MIT
// The pairs file of `genflow eval` (the format of $GENFLOW_DATA/pairs.json), read and checked
// whole before any pair is matched.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "genflow/io/read_part_model.h"

namespace genflow::cli {

/// One pair of a pairs file, its paths resolved against the data directory.
struct EvalPair {
    std::string name;                     ///< a plain file name: it names the pair's outputs
    std::filesystem::path template_mesh;  ///< "template"
    std::filesystem::path ground_truth;   ///< "target_ground_truth": vertex i matches vertex i
    std::optional<std::filesystem::path> target_remeshed;  ///< "target_remeshed", if given
    double target_simplified = 0;    ///< else the share of the ground truth's vertices, in (0, 1]
    std::optional<PartFiles> parts;  ///< "template_parts" and its companions, if given
};

/// Reads `file`: a JSON array of pair objects, each with the strings "name", "template",
/// "target_ground_truth", and "target_remeshed" or the number "target_simplified"; optionally
/// "template_parts", "template_parts_pose", "template_part_labels", "template_part_weights".
/// Paths are relative to `base`. Only the pairs named in `only` are returned, in the file's
/// order (all of them when it is empty).
/// \throws IoError "<file>: <problem>" for a file that cannot be read, is not such an array, has
///         a field of the wrong kind, a name that is not a plain file name (it names outputs:
///         no '/', not starting with '.', no control character) or a name twice; "<file>: no pair
///         named ..." for a name of `only` the file lacks.
[[nodiscard]] std::vector<EvalPair> read_pairs_file(const std::filesystem::path& file,
                                                    const std::filesystem::path& base,
                                                    const std::vector<std::string>& only = {});

}  // namespace genflow::cli
