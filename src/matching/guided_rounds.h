// SPDX-License-Identifier: MIT
// The coarsest level's guided rounds from one start: a flow of d_H augmented with the heat
// kernel signatures (which keep a limb off the wrong one nearby), then, from the functional
// map that match implies, flows augmented with the carried-over eigenfunctions (which tell left
// from right) at each stiffness of the stretching energy; the result that disagrees least with
// the target intrinsically is kept. Every guided flow is followed by one on the plain d_H.
#pragma once

#include <atomic>
#include <utility>
#include <vector>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/flows/flow.h"
#include "genflow/matching/match.h"
#include "matching/level_flow.h"
#include "matching/prepare.h"
#include "matching/spectral_descriptors.h"

namespace genflow::detail {

/// Whether the coarsest level runs guided rounds (MatchOptions::guided.signature_guidance):
/// measured per prior, h1, articulated and isometric gain; the quasi-rigid flow pulled a rigidly
/// moved limb 7 % off; L2 stays the unguided baseline.
[[nodiscard]] bool runs_guided_rounds(const MatchOptions& options);

/// The metric the guided rounds flow in. The quasi-isometric prior's rounds end too far from
/// the target for their disagreement to rank them, so it decides in the H1 metric, as the
/// selection flows do, and its kept result then flows on in its own (docs/matching.md).
[[nodiscard]] MatchPrior guided_prior(MatchPrior prior);

/// Where one start's guided rounds begin.
struct GuidedStart {
    Similarity placement;  ///< the start's similarity of the coarsest template
    /// Where the start's selection flow ended, if it had one: the functional map is also
    /// estimated from it.
    const Eigen::MatrixX3d* selection = nullptr;
    /// An intrinsic start's placement of the coarsest template: the map is estimated from it too.
    const Eigen::MatrixX3d* intrinsic = nullptr;
    /// Where the flows start, if not at `placement` applied to the template (a match again from
    /// a result).
    const TriangleMesh* from = nullptr;
    /// The last round guided by the signatures alone, as the signature fallback's is (a match
    /// again from a result that came from it).
    bool signatures_alone = false;
};

/// One start's result: the coarsest level's flow (all its steps counted, its energies the plain
/// d_H from the start on), the stretch weight and eigenfunction guidance kept, how far it
/// disagrees with the target, and whether the signature fallback gave it.
struct GuidedMatch {
    FlowResult flow;
    double stretch_weight = 0;
    double eigenfunction_guidance = 0;
    double disagreement = 0;
    bool signatures_alone = false;
};

class GuidedRounds {
public:
    /// The rounds on the coarsest level of `pyramid`, with `spectral` analysing that level;
    /// all kept by reference. `diagonal` is the target's bounding-box diagonal.
    GuidedRounds(const std::vector<Level>& pyramid, const LevelFlows& flows,
                 const SpectralDescriptors& spectral, const MatchOptions& options, double diagonal,
                 const std::atomic<bool>& cancelled);

    /// The rounds from `start`; `reports`: whether its first flow calls options.progress.
    [[nodiscard]] GuidedMatch match(const GuidedStart& start, bool reports) const;

private:
    using Guidances = std::vector<std::pair<PointDescriptors, double>>;

    [[nodiscard]] FlowResult guided_then_plain(const TriangleMesh& from,
                                               const Similarity& placement,
                                               const PointDescriptors& descriptors,
                                               double stretch_weight, bool reports) const;
    [[nodiscard]] GuidedMatch last_round(const TriangleMesh& from, const Similarity& placement,
                                         const Guidances& guidances, int first_steps,
                                         bool reports) const;
    [[nodiscard]] GuidedMatch eigenfunction_rounds(const GuidedStart& start,
                                                   const TriangleMesh& from, bool reports) const;

    const std::vector<Level>& pyramid_;
    const LevelFlows& flows_;
    const SpectralDescriptors& spectral_;
    const MatchOptions& options_;
    double diagonal_;
    const std::atomic<bool>& cancelled_;
    MatchPrior prior_;
    PointDescriptors signatures_;  // of the coarsest template level at rest
};

}  // namespace genflow::detail
