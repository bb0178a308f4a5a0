// SPDX-License-Identifier: MIT
// The matcher's coarsest level: where the template is put on the target as a whole, so where a
// match is right or wrong. The rigid starts flow briefly and the one whose signatures agree
// best goes through the guided rounds (guided_rounds.h), beside the second opinion from an
// intrinsic start; a doubtful winner is matched again from further intrinsic starts, and one
// with limbs on each other's places from its limbs exchanged. The rules that compare the
// contenders are in selection.h.
#pragma once

#include <atomic>
#include <optional>

#include "genflow/flows/flow.h"
#include "genflow/matching/match.h"
#include "matching/level_flow.h"
#include "matching/prepare.h"
#include "matching/spectral_descriptors.h"
#include "matching/stopwatch.h"

namespace genflow::detail {

/// The coarsest level's result and what was chosen on the way (as MatchResult reports it).
struct CoarsestMatch {
    FlowResult flow;   ///< the kept result; its steps count every flow of the level
    Similarity start;  ///< the start it came from, which places every level at rest
    double stretch_weight = 0;
    double eigenfunction_guidance = 0;
    bool signature_fallback = false;
    bool second_opinion = false;
    std::optional<double> second_opinion_disagreement = std::nullopt;
    int alternative_starts = 0;
    int alternative_start = 0;
    int swapped_limbs = 0;
};

/// The coarsest level of `prepared`'s pyramid matched. `spectral` analyses that level; it is
/// needed with several starts or guided rounds (runs_guided_rounds()), else may be null.
/// `clock` times the level's stages (MatchResult::stage_times).
[[nodiscard]] CoarsestMatch match_coarsest_level(const Prepared& prepared, const LevelFlows& flows,
                                                 const SpectralDescriptors* spectral,
                                                 const MatchOptions& options, double diagonal,
                                                 const std::atomic<bool>& cancelled,
                                                 StageClock& clock);

}  // namespace genflow::detail
