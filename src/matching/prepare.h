// SPDX-License-Identifier: MIT
// The matcher's first stage: the inputs prepared for the flows. The rigid starts (global
// alignment hypotheses), the scale the intrinsic starts take, and the pyramid of coarsened
// template and target levels (paper §6.4).
#pragma once

#include <optional>
#include <vector>

#include "genflow/matching/match.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/matching/rigid_alignment.h"
#include "matching/stopwatch.h"

namespace genflow::detail {

/// Template and target at one resolution; `embedding` places this level's template in the
/// next coarser one (empty on the coarsest).
struct Level {
    TriangleMesh template_mesh;
    TriangleMesh target;
    Embedding embedding;
    std::vector<Eigen::Index> original_vertex;  ///< template vertex of each level vertex
};

/// The level's template at rest, placed by `placement` (a start's similarity).
[[nodiscard]] TriangleMesh placed_template(const Level& level, const Similarity& placement);

/// What the flows start from.
struct Prepared {
    /// The rigid starts, best first (MatchOptions::starts, alignment_candidates); the identity
    /// alone without alignment.
    std::vector<Similarity> starts;
    /// The scale the intrinsic starts take where the areas mislead (a rough target or
    /// template): the volumes' (similarity_scale.h); none where the areas' scale holds.
    std::optional<double> volume_scale;
    /// Finest first (build_pyramid()).
    std::vector<Level> pyramid;
};

/// The rigid starts, the intrinsic starts' scale and the pyramid of `template_mesh` and
/// `target` (checked by match()); `clock` times the stages "alignment" and "pyramid".
[[nodiscard]] Prepared prepare(const TriangleMesh& template_mesh, const TriangleMesh& target,
                               const MatchOptions& options, StageClock& clock);

}  // namespace genflow::detail
