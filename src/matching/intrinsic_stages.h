// SPDX-License-Identifier: MIT
// The matcher's stages that read the target intrinsically, switched off together.
#pragma once

#include "genflow/matching/match.h"

namespace genflow::detail {

/// `options` with every stage that reads the target through its signatures, eigenfunctions or
/// the maps they imply switched off: the guided rounds, second opinions, limb exchanges, the
/// guided refinement, turned-back parts, fits to the fine map, the signatures' reading and
/// counterparts. What is left is the flow of d_H under the prior (and the rigid starts).
[[nodiscard]] inline MatchOptions without_intrinsic_stages(MatchOptions options) {
    options.guided.enabled = false;
    options.second_opinion.enabled = false;
    options.limb_swaps.enabled = false;
    options.refinement.enabled = false;
    options.turn_back.enabled = false;
    options.map_fit.enabled = false;
    options.signatures_reading.enabled = false;
    options.counterparts.enabled = false;
    return options;
}

}  // namespace genflow::detail
