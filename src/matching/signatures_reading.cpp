// SPDX-License-Identifier: MIT
#include "matching/signatures_reading.h"

#include "genflow/exceptions.h"
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

namespace {

// Per point, the corner of its face it lies nearest to (the largest barycentric coordinate).
std::vector<Eigen::Index> nearest_corners(const std::vector<SurfacePoint>& points,
                                          const TriangleMesh& mesh) {
    std::vector<Eigen::Index> corners;
    corners.reserve(points.size());
    for (const SurfacePoint& point : points) {
        Eigen::Index corner = 0;
        point.barycentric.maxCoeff(&corner);
        corners.push_back(mesh.F(point.face, corner));
    }
    return corners;
}

}  // namespace

ReadingJudge::ReadingJudge(const FinestBases& bases, const TriangleMesh& template_mesh,
                           const TriangleMesh& target, bool orientation)
    : bases_(bases), target_(target) {
    if (!orientation) {
        return;
    }
    try {
        orientation_.emplace(template_mesh, target);
    } catch (const SolverError&) {
        // The commutativity alone judges, then.
    }
}

ReadingScore ReadingJudge::score(const Eigen::MatrixX3d& deformed) const {
    const std::vector<SurfacePoint> map = closest_points(deformed, target_);
    ReadingScore score;
    score.commutativity =
        laplacian_commutativity(bases_.template_basis, target_, bases_.target_basis, map);
    if (orientation_) {
        score.orientation_ratio = orientation_->ratio(nearest_corners(map, target_));
    }
    return score;
}

}  // namespace genflow::detail
