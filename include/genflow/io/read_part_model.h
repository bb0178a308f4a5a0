// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "genflow/matching/part_model.h"

namespace genflow {

/// The files that describe a template's parts (README, "Part files").
struct PartFiles {
    /// The part tree, JSON, in one of three layouts:
    ///  - {"parts": [{"name", "parent": name or null, "joint_center": [x, y, z]}, ...]}
    ///  - {"bones": [{"index", "parent_bone": index or null, "joint_center": [x, y, z]}, ...]}
    ///  - {"parts": [names], "parent": {name: name or null}, "joint_centers": {pose: {name:
    ///    [x, y, z]}}}, with `pose` choosing the entry (needed only if there are several).
    /// It may name its per-vertex file with "labels" or "weights" (relative to the JSON).
    std::filesystem::path tree;
    /// One part index (0-based) per line, line i for vertex i; `#` lines are comments.
    std::optional<std::filesystem::path> labels = {};
    /// Lines "vertex part weight" (sparse); the weights of each vertex must sum to 1.
    std::optional<std::filesystem::path> weights = {};
    /// Which entry of "joint_centers" to use in the third layout.
    std::string pose = {};
};

/// Reads a part model for a template of `vertices` vertices and checks it
/// (check_part_model()). Labels win over weights when both are given.
/// \throws IoError "<file>: <problem>" for unreadable or malformed files and for models that do
///         not fit the template (wrong vertex count, cycles, labels out of range, weights that
///         do not sum to 1, missing per-vertex file).
[[nodiscard]] PartModel read_part_model(const PartFiles& files, Eigen::Index vertices);

}  // namespace genflow
