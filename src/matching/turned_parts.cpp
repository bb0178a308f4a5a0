// SPDX-License-Identifier: MIT
#include "matching/turned_parts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/mesh/edges.h"
#include "genflow/operators/mesh_size.h"
#include "mesh/union_find.h"
#include "numerics/nearest_orthogonal.h"

namespace genflow::detail {

namespace {

// The orthogonal map R (a rotation, or with `reflection` possibly a reflection) that best takes
// the rows of `from` onto those of `to`, both centred (row vectors: from R ≈ to), and the root
// mean square residual.
struct OrthogonalFit {
    Eigen::Matrix3d map;
    double residual = 0;
};

OrthogonalFit orthogonal_fit(const Eigen::MatrixX3d& from, const Eigen::MatrixX3d& to,
                             bool reflection) {
    const Eigen::MatrixX3d a = from.rowwise() - from.colwise().mean();
    const Eigen::MatrixX3d b = to.rowwise() - to.colwise().mean();
    OrthogonalFit fit;
    fit.map = nearest_orthogonal(a.transpose() * b, !reflection);
    fit.residual = std::sqrt((a * fit.map - b).squaredNorm() / static_cast<double>(a.rows()));
    return fit;
}

}  // namespace

std::vector<TurnedPart> find_turned_parts(const TriangleMesh& template_rest,
                                          const Eigen::MatrixX3d& deformed,
                                          const TriangleMesh& target, const VertexMap& map,
                                          const TurnedPartOptions& options) {
    if (deformed.rows() != template_rest.V.rows() ||
        (map.functions > 0 &&
         static_cast<Eigen::Index>(map.target_vertex.size()) != deformed.rows())) {
        throw InvalidInput("find_turned_parts: the deformed template or its map has not the " +
                           std::to_string(template_rest.V.rows()) + " vertices of the template");
    }
    if (map.functions < 1) {
        return {};
    }
    const Eigen::MatrixX3d mapped = target.V(map.target_vertex, Eigen::all);

    // The disputed vertices, in connected parts.
    const double reach = options.disputed_distance * bounding_box_diagonal(target);
    std::vector<char> disputed(static_cast<std::size_t>(deformed.rows()));
    for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
        disputed[static_cast<std::size_t>(i)] = (mapped.row(i) - deformed.row(i)).norm() > reach;
    }
    UnionFind parts(disputed.size());
    const Eigen::MatrixX2i edges = unique_edges(template_rest.F);
    for (Eigen::Index e = 0; e < edges.rows(); ++e) {
        const auto a = static_cast<std::size_t>(edges(e, 0));
        const auto b = static_cast<std::size_t>(edges(e, 1));
        if (disputed[a] && disputed[b]) {
            parts.unite(a, b);
        }
    }
    std::vector<std::vector<Eigen::Index>> members(disputed.size());
    for (std::size_t i = 0; i < disputed.size(); ++i) {
        if (disputed[i]) {
            members[parts.find(i)].push_back(static_cast<Eigen::Index>(i));
        }
    }

    const Eigen::VectorXd& masses = map.template_masses;
    const double min_area = map.resolved_area();
    std::vector<std::pair<double, TurnedPart>> found;
    for (std::vector<Eigen::Index>& vertices : members) {
        if (vertices.size() < 4 || masses(vertices).sum() < min_area) {
            continue;
        }
        const Eigen::MatrixX3d rest = template_rest.V(vertices, Eigen::all);
        const Eigen::MatrixX3d mapped_part = mapped(vertices, Eigen::all);
        const OrthogonalFit mirrored = orthogonal_fit(rest, mapped_part, true);
        if (mirrored.map.determinant() < 0 &&
            mirrored.residual <
                options.reflection_ratio * orthogonal_fit(rest, mapped_part, false).residual) {
            continue;  // the map mirrors this part (a nearly symmetric head, left for right)
        }
        // The turn that explains the map best, refitted to the vertices it explains (a hand's
        // turn, not the partial one of the forearm it blends into).
        std::vector<Eigen::Index> core = vertices;
        for (int round = 0; round < 3 && core.size() >= 4; ++round) {
            const Eigen::MatrixX3d from_core = deformed(core, Eigen::all);
            const Eigen::MatrixX3d to_core = mapped(core, Eigen::all);
            const OrthogonalFit turn_fit = orthogonal_fit(from_core, to_core, false);
            const Eigen::RowVector3d from_centre = from_core.colwise().mean();
            const Eigen::RowVector3d to_centre = to_core.colwise().mean();
            std::vector<Eigen::Index> explained;
            for (const Eigen::Index v : vertices) {
                const Eigen::RowVector3d turned =
                    (deformed.row(v) - from_centre) * turn_fit.map + to_centre;
                if ((turned - mapped.row(v)).norm() < reach) {
                    explained.push_back(v);
                }
            }
            core = std::move(explained);
        }
        const double core_area = masses(core).sum();
        if (core.size() < 4 || core_area < min_area) {
            continue;
        }
        const Eigen::MatrixX3d from_points = deformed(core, Eigen::all);
        const Eigen::MatrixX3d to_points = mapped(core, Eigen::all);
        // Row vectors turn by R; column vectors by Rᵀ.
        const Eigen::AngleAxisd turn(
            Eigen::Matrix3d(orthogonal_fit(from_points, to_points, false).map.transpose()));
        if (!(turn.angle() > options.min_angle)) {
            continue;
        }
        found.emplace_back(core_area, TurnedPart{std::move(core), from_points.colwise().mean(),
                                                 to_points.colwise().mean(), turn,
                                                 std::move(vertices), mapped_part});
    }
    std::sort(found.begin(), found.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<TurnedPart> result;
    for (auto& [part_area, part] : found) {
        result.push_back(std::move(part));
    }
    return result;
}

Eigen::MatrixX3d turned_back(const TriangleMesh& template_rest, const Eigen::MatrixX3d& deformed,
                             const std::vector<TurnedPart>& parts) {
    const std::vector<std::vector<Eigen::Index>> neighbours =
        vertex_neighbours(template_rest.F, template_rest.V.rows());
    const std::size_t n = neighbours.size();
    Eigen::MatrixX3d result = deformed;
    for (const TurnedPart& part : parts) {
        // The part's motion x ↦ R x + t as a screw: a turn about the line through `pivot` along
        // the axis a, then a slide along it. A share of it turns by that share of the angle
        // about the same line and slides that share of the way, which undoes a joint's partial
        // turn exactly where a turn about the centroid and a share of the shift would not.
        const double angle = part.turn.angle();
        const Eigen::Vector3d axis = part.turn.axis();
        const Eigen::Vector3d motion = part.to_centre.transpose() -
                                       part.turn.toRotationMatrix() * part.from_centre.transpose();
        const double slide = motion.dot(axis);
        const Eigen::Vector3d across = motion - slide * axis;
        const Eigen::Vector3d pivot =
            angle > 1e-9
                ? Eigen::Vector3d(0.5 * (across + axis.cross(across) / std::tan(angle / 2)))
                : Eigen::Vector3d::Zero();
        const auto partly_turned = [&](Eigen::Index v, double weight) {
            const Eigen::Vector3d point = result.row(v).transpose();
            if (!(angle > 1e-9)) {
                return Eigen::RowVector3d((point + weight * motion).transpose());
            }
            const Eigen::Matrix3d rotation =
                Eigen::AngleAxisd(weight * angle, axis).toRotationMatrix();
            return Eigen::RowVector3d(
                (rotation * (point - pivot) + pivot + weight * slide * axis).transpose());
        };
        // Per vertex of the region, the share that takes it nearest to where the map puts it
        // (of 0, 1/20, ..., 1), smoothed over the region (1 on the part, 0 outside the region).
        // The short way round: the long way fits the map's places closer but ends farther from
        // the truth (docs/measurements.md, "Turned parts").
        constexpr int kShares = 20;
        std::vector<char> role(n, 0);  // 0 outside, 1 region, 2 part
        std::vector<double> fitted(n, 0);
        for (std::size_t k = 0; k < part.region.size(); ++k) {
            const Eigen::Index v = part.region[k];
            role[static_cast<std::size_t>(v)] = 1;
            double nearest = std::numeric_limits<double>::infinity();
            for (int j = 0; j <= kShares; ++j) {
                const double share = static_cast<double>(j) / kShares;
                const double distance =
                    (partly_turned(v, share) - part.region_mapped.row(static_cast<Eigen::Index>(k)))
                        .norm();
                if (distance < nearest) {
                    nearest = distance;
                    fitted[static_cast<std::size_t>(v)] = share;
                }
            }
        }
        for (const Eigen::Index v : part.vertices) {
            role[static_cast<std::size_t>(v)] = 2;
        }
        std::vector<double> weight(n, 0);
        for (std::size_t v = 0; v < n; ++v) {
            weight[v] = role[v] == 2 ? 1.0 : fitted[v];
        }
        // Each region vertex: half its fitted share, half its neighbours' mean weight, over
        // three Jacobi sweeps (the map is noisy per vertex; smoothing much more spreads a
        // joint's twist beyond where it is).
        constexpr int kSweeps = 3;
        for (int sweep = 0; sweep < kSweeps; ++sweep) {
            std::vector<double> next = weight;
            for (std::size_t v = 0; v < n; ++v) {
                if (role[v] == 1 && !neighbours[v].empty()) {
                    double sum = 0;
                    for (const Eigen::Index w : neighbours[v]) {
                        sum += weight[static_cast<std::size_t>(w)];
                    }
                    next[v] =
                        0.5 * fitted[v] + 0.5 * sum / static_cast<double>(neighbours[v].size());
                }
            }
            weight = std::move(next);
        }
        for (std::size_t v = 0; v < n; ++v) {
            if (role[v] > 0) {
                const auto row = static_cast<Eigen::Index>(v);
                result.row(row) = partly_turned(row, weight[v]);
            }
        }
    }
    return result;
}

}  // namespace genflow::detail
