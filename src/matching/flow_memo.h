// SPDX-License-Identifier: MIT
// The flows a match asks for more than once, run once. A flow of LevelFlows is a function of its
// request alone (the level, where it starts, its steps, the placement, the prior, the
// descriptors and the stretch weight), and the signatures' reading asks again for every flow of
// the first reading that the eigenfunctions did not guide: the rigid starts' selection flows and
// a doubtful contender's signature fallback (docs/matching.md, "The signatures' reading").
#pragma once

#include <Eigen/Core>
#include <mutex>
#include <optional>
#include <vector>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/flows/flow.h"
#include "genflow/matching/match.h"
#include "genflow/matching/rigid_alignment.h"

namespace genflow::detail {

/// One flow as LevelFlows::flow() is asked for it; every pointer is borrowed for the call.
struct FlowRequest {
    int level = 0;
    const Eigen::MatrixX3d* start = nullptr;
    int iterations = 0;
    const Similarity* placement = nullptr;
    MatchPrior prior = MatchPrior::H1;
    const PointDescriptors* descriptors = nullptr;
    double stretch_weight = 0;
};

/// The results of the flows one match ran, found again by an exact comparison of the request.
/// One memo serves the flows of one pyramid and one set of options, apart from the guidance
/// weights, which reach a flow through its descriptors only. Safe to use from the threads of
/// run_side_by_side().
class FlowMemo {
public:
    /// The result of a flow run with the same request, if one was kept.
    [[nodiscard]] std::optional<FlowResult> find(const FlowRequest& request) const;

    /// Keeps `result` as the flow of `request` (a result already kept for it stays).
    void keep(const FlowRequest& request, const FlowResult& result);

    /// How many requests were answered from the memo.
    [[nodiscard]] int reused() const;

private:
    struct Entry {
        int level = 0;
        Eigen::MatrixX3d start;
        int iterations = 0;
        Similarity placement;
        MatchPrior prior = MatchPrior::H1;
        PointDescriptors descriptors;
        double stretch_weight = 0;
        FlowResult result;

        [[nodiscard]] bool answers(const FlowRequest& request) const;
    };

    /// The entry that answers `request`, or null; the caller holds `mutex_`.
    [[nodiscard]] const Entry* entry_for(const FlowRequest& request) const;

    mutable std::mutex mutex_;
    std::vector<Entry> entries_;
    mutable int reused_ = 0;
};

}  // namespace genflow::detail
