// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "genflow/parts/part_model.h"

namespace genflow {

/// The files that describe a template's parts (docs/matching.md, "Part files").
struct PartFiles {
    /// The part tree, JSON, in one of three layouts:
    ///  - {"parts": [{"name", "parent": name or null, "joint_center": [x, y, z]}, ...]},
    ///    optionally with "poses": {pose: {name: {"world_transform_4x4": rows}}} (MakeHuman)
    ///  - {"bones": [{"index", "parent_bone": index or null, "joint_center": [x, y, z]}, ...]},
    ///    optionally with "pose_bone_transforms_4x4": {pose: [rows per bone]} (libigl)
    ///  - {"parts": [names], "parent": {name: name or null}, "joint_centers": {pose: {name:
    ///    [x, y, z]}}} (SMPL), one entry needed (the only one, or the template's pose).
    /// The joint centres of the first two are at rest; the template's pose, if the file has it,
    /// moves each by the transform of its part (the part below the joint), as the rig posed it.
    /// It may name its per-vertex file with "labels" or "weights" (relative to the JSON).
    std::filesystem::path tree;
    /// One part index (0-based) per line, line i for vertex i; `#` lines are comments.
    std::optional<std::filesystem::path> labels = {};
    /// Lines "vertex part weight" (sparse); the weights of each vertex must sum to 1.
    std::optional<std::filesystem::path> weights = {};
    /// The pose the template is in: a key of the file's poses ("joint_centers", "poses" or
    /// "pose_bone_transforms_4x4"); refused if the file does not have it. Empty: the pose that
    /// `template_name` or its last '_'-separated word names ("arm_pose1": "pose1"), if the file
    /// has it; else the rest pose (or, in the third layout, its only entry).
    std::string pose = {};
    /// The template's file name without its extension, to find its pose by.
    std::string template_name = {};
};

/// Reads a part model for a template of `vertices` vertices and checks it
/// (check_part_model()). Labels win over weights when both are given.
/// \throws IoError "<file>: <problem>" for unreadable or malformed files and for models that do
///         not fit the template (wrong vertex count, cycles, labels out of range, weights that
///         do not sum to 1, missing per-vertex file).
[[nodiscard]] PartModel read_part_model(const PartFiles& files, Eigen::Index vertices);

}  // namespace genflow
