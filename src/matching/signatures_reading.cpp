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

ReadingJudge::ReadingJudge(const TriangleMesh& template_mesh, const TriangleMesh& target)
    : target_(target),
      template_basis_(laplacian_eigenbasis(template_mesh, kCommutativityFunctions + 1)),
      target_basis_(laplacian_eigenbasis(target, kCommutativityFunctions + 1)) {}

double ReadingJudge::commutativity(const Eigen::MatrixX3d& deformed) const {
    return laplacian_commutativity(template_basis_, target_, target_basis_,
                                   closest_points(deformed, target_));
}

}  // namespace genflow::detail
