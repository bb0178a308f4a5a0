// SPDX-License-Identifier: MIT
// A match onto a target that shows only part of the template (PartialTargetOptions): the
// options such a match runs with, and its choice among the rigid starts.
#pragma once

#include <vector>

#include "genflow/matching/match.h"

namespace genflow::detail {

/// Whether `options` match onto a partial target (their extent resolved by match()).
[[nodiscard]] bool matches_partial_target(const MatchOptions& options);

/// `options` with the extent resolved for `template_mesh` and `target` (shows_part_only()
/// where Automatic) and, for a partial target, the stages that read the target intrinsically
/// off, the rigid alignment one-sided and at the template's scale.
[[nodiscard]] MatchOptions resolved_for_target(const MatchOptions& options,
                                               const TriangleMesh& template_mesh,
                                               const TriangleMesh& target);

/// The rigid starts ordered by the facing distance of the template they place: the one-sided
/// d_H from `target` to it, points compared with their normals (PartialTargetOptions::
/// normal_weight), low where the template covers the target facing the same way. A stable order.
void rank_by_facing_distance(std::vector<Similarity>& starts, const TriangleMesh& template_mesh,
                             const TriangleMesh& target, const MatchOptions& options);

}  // namespace genflow::detail
