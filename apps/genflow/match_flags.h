// SPDX-License-Identifier: MIT
// The matcher's algorithm options on the command line (prior, levels, iterations, guidance,
// ...), shared by `genflow match`, `genflow benchmark` and `genflow eval`: declared once, so all
// three take the same flags with the same checks and help.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "genflow/matching/match.h"

namespace genflow::cli {

/// What the flags set; `resolved()` turns it into MatchOptions.
struct MatchFlags {
    std::string prior;  ///< empty: articulated with a part model, else h1
    MatchOptions match;
    bool no_align = false;
    bool no_turn_back = false;
    bool no_limb_swaps = false;
    bool no_landmark_spread = false;
    bool no_signature_fallback = false;
    bool no_signatures_reading = false;
    bool report_orientation = false;
    bool no_counterparts = false;
    std::string target_extent = "auto";   ///< to_string(TargetExtent)
    std::string first_step = "doubling";  ///< MatchOptions::first_step
};

/// Declares `--prior` on `command`, writing into `flags` (which must outlive the parse).
void add_prior_flag(CLI::App& command, MatchFlags& flags);

/// Declares the algorithm's flags (all but the prior) on `command`, writing into `flags`.
void add_match_flags(CLI::App& command, MatchFlags& flags);

/// The options the flags ask for; `has_parts` says whether a part model will be given (the
/// default prior is then articulated).
[[nodiscard]] MatchOptions resolved(const MatchFlags& flags, bool has_parts);

}  // namespace genflow::cli
