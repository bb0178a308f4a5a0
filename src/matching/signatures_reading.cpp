// SPDX-License-Identifier: MIT
#include "matching/signatures_reading.h"

#include "genflow/matching/correspondence.h"
#include "genflow/matching/laplacian_commutativity.h"
#include "matching/guided_rounds.h"

namespace genflow::detail {

bool reads_with_signatures(const MatchOptions& options) {
    return options.signatures_reading.enabled && runs_guided_rounds(options) &&
           options.guided.eigenfunction_guidance > 0;
}

MatchOptions signatures_reading_options(const MatchOptions& options) {
    MatchOptions signatures = options;
    signatures.guided.eigenfunction_guidance = 0;
    return signatures;
}

ReadingJudge::ReadingJudge(const FinestBases& bases, const TriangleMesh& target)
    : bases_(bases), target_(target) {}

double ReadingJudge::commutativity(const Eigen::MatrixX3d& deformed) const {
    return laplacian_commutativity(bases_.template_basis, target_, bases_.target_basis,
                                   closest_points(deformed, target_));
}

}  // namespace genflow::detail
