// SPDX-License-Identifier: MIT
#pragma once

#include <optional>
#include <string>

#include "genflow/mesh.h"

namespace genflow {

/// How much of the template's surface a match's target shows (MatchOptions::partial).
enum class TargetExtent {
    Automatic,  ///< decided by shows_part_only()
    Complete,   ///< all of it: the paper's symmetric d_H, and every stage of the matcher
    Partial,    ///< part of it: a single view, a scan with large holes, a limb cut off
};

/// "auto", "complete", "partial".
[[nodiscard]] const char* to_string(TargetExtent extent);
/// The extent named by `name` (as to_string() spells it), or nothing.
[[nodiscard]] std::optional<TargetExtent> parse_target_extent(const std::string& name);

/// How match() treats a target that shows only part of the template (docs/matching.md,
/// "Partial targets"). Such a match flows by the one-sided d_H (every target point near the
/// template; PseudoHausdorffOptions::moving_coverage 0), so that the template's unseen parts
/// follow the prior instead of being pulled onto whatever surface is near; it keeps every
/// component of the target; it takes the template at its own scale, since a part's area does
/// not tell the whole's size; it chooses among the rigid starts by where the template's normals
/// agree with the target's; and it leaves out the stages that read the target intrinsically
/// (signatures, eigenfunctions, the maps they imply), which a boundary changes.
struct PartialTargetOptions {
    TargetExtent extent = TargetExtent::Automatic;
    /// When the rigid starts are ranked, points count as near only if close and facing alike:
    /// a unit normal weighs this many target diagonals, so two points facing opposite ways are
    /// at least half a diagonal apart, more than the two sides of any part of a body. A start
    /// that shows the template's back to a view of the front then ranks low (0.1–0.4 chose
    /// alike on sixty single views; docs/matching.md, "Partial targets").
    double normal_weight = 0.25;
};

/// Whether `target` shows only part of `template_mesh`'s surface: its boundary is longer, per
/// √area, than the template's by more than a scanner's small holes and an open wrist make
/// (kShortBoundary of similarity_scale.h, 1.5); one side of a shape, or a shape cut through its
/// middle, has far more. Scale-free; the template's own boundary (an open template) does not
/// count.
/// \throws InvalidInput if a mesh is invalid or has zero area.
[[nodiscard]] bool shows_part_only(const TriangleMesh& template_mesh, const TriangleMesh& target);

}  // namespace genflow
