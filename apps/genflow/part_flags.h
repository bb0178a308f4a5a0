// SPDX-License-Identifier: MIT
// The template's part model on the command line (--parts, --part-labels, --part-weights,
// --parts-pose), shared by `genflow match` and `genflow batch`.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "genflow/parts/part_model.h"

namespace genflow::cli {

/// What the flags name; all empty: no part model.
struct PartFlags {
    std::string tree;
    std::string labels;
    std::string weights;
    std::string pose;
};

/// Declares the part flags on `command`, writing into `flags` (which must outlive the parse).
void add_part_flags(CLI::App& command, PartFlags& flags);

/// The part model the flags name for the template at `template_path` of `vertices` vertices,
/// read and checked (read_part_model()); nothing without --parts.
[[nodiscard]] std::optional<PartModel> part_model(const PartFlags& flags,
                                                  const std::string& template_path,
                                                  Eigen::Index vertices);

}  // namespace genflow::cli
