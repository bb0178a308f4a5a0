// SPDX-License-Identifier: MIT
#include "matching/spread_landmarks.h"

#include <cmath>

#include "genflow/mesh/face_selection.h"
#include "genflow/operators/area.h"
#include "spatial/farthest_points.h"
#include "spatial/surface_paths.h"

namespace genflow::detail {

namespace {

// Three distances fix a point of a surface (up to a reflection, which the landmarks' others and
// the flow's d_H settle); fewer leave circles of candidates.
constexpr std::size_t kFewestToSpread = 3;

// Per vertex of `mesh`, exp(−(d_k/σ)²) of its geodesic distance d_k to each of `sources` (along
// the edges; 0 on components without the source).
Eigen::MatrixXd geodesic_gaussians(const TriangleMesh& mesh,
                                   const std::vector<Eigen::Index>& sources, double sigma) {
    const ChordGraph edges = chord_graph(mesh, 1);
    Eigen::MatrixXd gaussians(mesh.V.rows(), static_cast<Eigen::Index>(sources.size()));
    for (std::size_t k = 0; k < sources.size(); ++k) {
        const Eigen::ArrayXd d = path_lengths_from(edges, sources[k]).array() / sigma;
        gaussians.col(static_cast<Eigen::Index>(k)) = (-d.square()).exp().matrix();
    }
    return gaussians;
}

// The row of `rows` nearest `query`, by brute force (a few thousand rows, one pass each).
template <typename Rows, typename Query>
Eigen::Index nearest_row(const Rows& rows, const Query& query) {
    Eigen::Index nearest = 0;
    (rows.rowwise() - query).rowwise().squaredNorm().minCoeff(&nearest);
    return nearest;
}

}  // namespace

std::vector<Landmark> spread_landmarks(const TriangleMesh& template_mesh,
                                       const TriangleMesh& target,
                                       const std::vector<Landmark>& landmarks, Eigen::Index count) {
    if (landmarks.size() < kFewestToSpread || count <= 0) {
        return landmarks;
    }
    const std::vector<Eigen::Index> template_rows =
        vertices_used_by(template_mesh.F, template_mesh.V.rows());
    const std::vector<Eigen::Index> target_rows = vertices_used_by(target.F, target.V.rows());
    const Eigen::MatrixX3d target_points = target.V(target_rows, Eigen::all);
    // Each landmark on its template vertex and on the target's used vertex nearest its point.
    std::vector<Eigen::Index> from;
    std::vector<Eigen::Index> on_target;  // rows of target_points
    std::vector<Eigen::Index> to;
    for (const Landmark& landmark : landmarks) {
        from.push_back(landmark.vertex);
        on_target.push_back(nearest_row(target_points, landmark.target_point.transpose()));
        to.push_back(target_rows[static_cast<std::size_t>(on_target.back())]);
    }
    const double sigma =
        std::sqrt(surface_area(template_mesh) / static_cast<double>(landmarks.size()));
    const Eigen::MatrixXd candidates =
        geodesic_gaussians(template_mesh, from, sigma)(template_rows, Eigen::all);
    const Eigen::MatrixXd target_gaussians = geodesic_gaussians(target, to, sigma);

    std::vector<Landmark> spread = landmarks;
    for (const Eigen::Index sample : farthest_points(target_points, on_target.front(), count)) {
        const Eigen::Index point = target_rows[static_cast<std::size_t>(sample)];
        const Eigen::Index match = nearest_row(candidates, target_gaussians.row(point));
        spread.push_back(
            {template_rows[static_cast<std::size_t>(match)], target.V.row(point).transpose()});
    }
    return spread;
}

}  // namespace genflow::detail
