// SPDX-License-Identifier: MIT
// The flow of one level of the pyramid: steepest descent of d_H (paper eq. 14), augmented with
// descriptors where they guide it and with the stretching energy where it holds edge lengths,
// in the prior's metric. Every stage of the matcher flows through this.
#pragma once

#include <atomic>
#include <string_view>
#include <vector>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/flows/flow.h"
#include "genflow/matching/match.h"
#include "matching/flow_memo.h"
#include "matching/prepare.h"

namespace genflow::detail {

/// What MatchResult reports of a level's flow (`flow`, on `level`, in `seconds`).
[[nodiscard]] MatchLevel level_report(const Level& level, const FlowResult& flow, double seconds);

class LevelFlows {
public:
    /// Flows on the levels of `pyramid` (finest first) with `options`; `diagonal` is the
    /// target's bounding-box diagonal. A flow whose progress call returns false sets
    /// `cancelled`, which stops the others. `memo`, if given, answers the coarsest level's flows
    /// it has seen and keeps those it has not (flow_memo.h). All are kept by reference.
    LevelFlows(const std::vector<Level>& pyramid, const MatchOptions& options, double diagonal,
               std::atomic<bool>& cancelled, FlowMemo* memo = nullptr)
        : pyramid_(pyramid),
          options_(options),
          diagonal_(diagonal),
          cancelled_(cancelled),
          memo_(memo) {}

    /// d_H to a level's target, with ε that many times its mean edge length.
    [[nodiscard]] PseudoHausdorffEnergy distance_to_target(
        const Level& level, double epsilon_factor, const PointDescriptors& descriptors) const;

    /// The flow of level `l` from `moved` (the template level's vertices, already placed).
    /// `placement`: the similarity that took the template level to `moved`'s rest frame.
    /// `descriptors`: the d_H augmented with them (signature_guidance), else the plain one.
    /// `stretch_weight` > 0 adds that times the diagonal times the level's EdgeLengthEnergy.
    /// `reports`: whether it calls options.progress; of flows run side by side, one does (the
    /// others only stop when it was cancelled).
    [[nodiscard]] FlowResult flow(int l, const TriangleMesh& moved, int iterations,
                                  const Similarity& placement, MatchPrior prior,
                                  const PointDescriptors& descriptors = {},
                                  double stretch_weight = 0, bool reports = true) const;

    /// The index of the coarsest level.
    [[nodiscard]] int coarsest() const { return count() - 1; }

    /// Tells options.stages (if set) that level `l` reached `stage` with `mesh`.
    void tell(int l, std::string_view stage, const TriangleMesh& mesh) const;

private:
    [[nodiscard]] int count() const { return static_cast<int>(pyramid_.size()); }

    /// flow() without the memo.
    [[nodiscard]] FlowResult run_flow(int l, const TriangleMesh& moved, int iterations,
                                      const Similarity& placement, MatchPrior prior,
                                      const PointDescriptors& descriptors, double stretch_weight,
                                      bool reports) const;

    const std::vector<Level>& pyramid_;
    const MatchOptions& options_;
    double diagonal_;
    std::atomic<bool>& cancelled_;
    FlowMemo* memo_;
};

}  // namespace genflow::detail
