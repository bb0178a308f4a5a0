// SPDX-License-Identifier: MIT
#include "genflow/mesh/boundary_loops.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "genflow/mesh/edges.h"
#include "genflow/operators/normals.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

// The boundary edges at one vertex: those entering it and those leaving it.
struct BoundaryCorner {
    std::vector<Eigen::Index> entering;
    std::vector<Eigen::Index> leaving;
};

// The angle of the direction from `pivot` to `towards` about `normal` (not zero),
// counter-clockwise.
double angle_about(const Eigen::Vector3d& normal, const Eigen::Vector3d& pivot,
                   const Eigen::Vector3d& towards) {
    const Eigen::Vector3d u = normal.unitOrthogonal();
    const Eigen::Vector3d v = normal.normalized().cross(u);
    const Eigen::Vector3d d = towards - pivot;
    return std::atan2(d.dot(v), d.dot(u));
}

// At a vertex where several loops meet, each entering edge paired with the leaving edge that
// bounds the same gap: the next unpaired one counter-clockwise from it. The edges in angular
// order are matched as brackets, going round twice so that pairs across the start are made.
void pair_across_gaps(const TriangleMesh& mesh, const Eigen::MatrixX2i& edges, int vertex,
                      const Eigen::Vector3d& normal, const BoundaryCorner& corner,
                      std::vector<Eigen::Index>& next) {
    const Eigen::Vector3d pivot = mesh.V.row(vertex).transpose();
    // (angle, edge, whether it enters)
    std::vector<std::tuple<double, Eigen::Index, bool>> around;
    for (const Eigen::Index e : corner.entering) {
        around.emplace_back(angle_about(normal, pivot, mesh.V.row(edges(e, 0)).transpose()), e,
                            true);
    }
    for (const Eigen::Index e : corner.leaving) {
        around.emplace_back(angle_about(normal, pivot, mesh.V.row(edges(e, 1)).transpose()), e,
                            false);
    }
    std::sort(around.begin(), around.end());
    std::vector<std::size_t> open;
    std::vector<bool> paired(around.size(), false);
    for (std::size_t step = 0; step < 2 * around.size(); ++step) {
        const std::size_t k = step % around.size();
        const auto& [angle, edge, enters] = around[k];
        if (paired[k]) {
            continue;
        }
        if (enters) {
            if (step < around.size()) {
                open.push_back(k);
            }
        } else if (!open.empty()) {
            const std::size_t from = open.back();
            open.pop_back();
            paired[from] = paired[k] = true;
            next[static_cast<std::size_t>(std::get<1>(around[from]))] = edge;
        }
    }
}

// For each boundary edge, the boundary edge that continues it (-1: none).
std::vector<Eigen::Index> continuations(const TriangleMesh& mesh, const Eigen::MatrixX2i& edges) {
    std::vector<BoundaryCorner> corners(static_cast<std::size_t>(mesh.V.rows()));
    for (Eigen::Index e = 0; e < edges.rows(); ++e) {
        corners[static_cast<std::size_t>(edges(e, 1))].entering.push_back(e);
        corners[static_cast<std::size_t>(edges(e, 0))].leaving.push_back(e);
    }
    std::vector<Eigen::Index> next(static_cast<std::size_t>(edges.rows()), -1);
    Eigen::MatrixX3d normals;
    for (std::size_t v = 0; v < corners.size(); ++v) {
        const BoundaryCorner& corner = corners[v];
        if (corner.entering.size() == 1 && corner.leaving.size() == 1) {
            next[static_cast<std::size_t>(corner.entering[0])] = corner.leaving[0];
        } else if (!corner.entering.empty() && !corner.leaving.empty()) {
            if (normals.rows() == 0) {
                normals = vertex_normals(mesh);
            }
            const Eigen::Vector3d normal = normals.row(static_cast<Eigen::Index>(v)).transpose();
            // Faces that cancel out about the vertex (folded onto each other) give no side to
            // turn about; any fixed one pairs the edges all the same.
            pair_across_gaps(mesh, edges, static_cast<int>(v),
                             normal.squaredNorm() > 0 ? normal : Eigen::Vector3d::UnitZ(), corner,
                             next);
        }
    }
    return next;
}

}  // namespace

std::vector<std::vector<int>> boundary_loops(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "boundary_loops");
    const Eigen::MatrixX2i edges = oriented_boundary_edges(mesh.F);
    const std::vector<Eigen::Index> next = continuations(mesh, edges);
    std::vector<bool> taken(next.size(), false);
    std::vector<std::vector<int>> loops;
    for (Eigen::Index start = 0; start < edges.rows(); ++start) {
        std::vector<int> loop;
        for (Eigen::Index e = start; e >= 0 && !taken[static_cast<std::size_t>(e)];
             e = next[static_cast<std::size_t>(e)]) {
            taken[static_cast<std::size_t>(e)] = true;
            loop.push_back(edges(e, 0));
        }
        if (!loop.empty()) {
            loops.push_back(std::move(loop));
        }
    }
    return loops;
}

}  // namespace genflow
