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
    Partial,    ///< part of it: a single view, a shape cut through its middle
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

/// Whether `target` shows only part of `template_mesh`'s surface: the holes its boundary loops
/// leave (hole_area(), each loop closed by a flat patch) make up more than a fifth of the closed
/// surface, hole_area / (area + hole_area), beyond the template's own. A single view of a body
/// leaves 0.27–0.42 (one side of a sphere 1/3); twenty palm-sized holes in a body, a ragged rim
/// or an open wrist leave at most 0.10, and such a scan is matched as a complete target, with
/// the intrinsic stages (docs/benchmarks.md, "Scans as they come"). Scale-free; a part cut off
/// across a narrow neck (a limb) leaves little and is not found.
/// \throws InvalidInput if a mesh is invalid or has zero area.
[[nodiscard]] bool shows_part_only(const TriangleMesh& template_mesh, const TriangleMesh& target);

}  // namespace genflow
