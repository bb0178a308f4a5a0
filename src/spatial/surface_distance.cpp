// SPDX-License-Identifier: MIT
#include "genflow/spatial/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/spatial/closest_point.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

struct Piece {
    Eigen::Vector3d corner[3];
    double distance[3];
    Eigen::Index face[3];  // the face of `to` nearest to each corner
};

// Everything a refinement step needs to know about the surface measured against.
struct Target {
    const TriangleMesh& mesh;
    const TriangleBvh& bvh;

    [[nodiscard]] double distance_to_face(const Eigen::Vector3d& p, Eigen::Index f) const {
        const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)).transpose();
        const Eigen::Vector3d b = mesh.V.row(mesh.F(f, 1)).transpose();
        const Eigen::Vector3d c = mesh.V.row(mesh.F(f, 2)).transpose();
        const Eigen::Vector3d w = closest_point_on_triangle(p, a, b, c);
        return (w[0] * a + w[1] * b + w[2] * c - p).norm();
    }
};

// A proven upper bound of d(·, to) over the triangle, the better of two arguments:
// - d is 1-Lipschitz: d(p) ≤ d(c_k) + |p − c_k| ≤ d(c_k) + (longest edge at c_k);
// - d(p) ≤ d(p, t) for any one face t, and d(·, t) is convex (distance to a convex set), so its
//   maximum over the triangle is at a corner: d(p) ≤ max_k d(c_k, t), tried for the faces
//   nearest to the corners. This one is tight on plateaus, where the first would refine forever.
double upper_bound(const Piece& piece, const Target& target) {
    double bound = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
        const double reach = std::max((piece.corner[k] - piece.corner[(k + 1) % 3]).norm(),
                                      (piece.corner[k] - piece.corner[(k + 2) % 3]).norm());
        bound = std::min(bound, piece.distance[k] + reach);
    }
    for (int candidate = 0; candidate < 3; ++candidate) {
        double worst = 0;
        for (int k = 0; k < 3 && worst < bound; ++k) {
            worst = std::max(worst, k == candidate ? piece.distance[k]
                                                   : target.distance_to_face(
                                                         piece.corner[k], piece.face[candidate]));
        }
        bound = std::min(bound, worst);
    }
    return bound;
}

// Pieces refined at most, per direction: beyond it the reported upper bound is the largest
// bound of what is left, still proven, just less tight.
constexpr std::size_t kRefinementBudget = 20'000'000;

void one_sided_hausdorff(const TriangleMesh& from, const Target& target, double tolerance,
                         OneSidedDistance& result) {
    const Eigen::Index n = from.V.rows();
    std::vector<SurfacePoint> nearest(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(dynamic, 256)
    for (Eigen::Index i = 0; i < n; ++i) {
        nearest[static_cast<std::size_t>(i)] = target.bvh.closest_point(from.V.row(i).transpose());
    }
    double lower = -1;
    const auto consider = [&](const Eigen::Vector3d& p, double d) {
        if (d > lower) {
            lower = d;
            result.farthest_point = p;
        }
    };
    std::vector<Piece> open;
    for (Eigen::Index f = 0; f < from.F.rows(); ++f) {
        Piece piece;
        for (int k = 0; k < 3; ++k) {
            const auto& found = nearest[static_cast<std::size_t>(from.F(f, k))];
            piece.corner[k] = from.V.row(from.F(f, k)).transpose();
            piece.distance[k] = found.distance;
            piece.face[k] = found.face;
            consider(piece.corner[k], piece.distance[k]);
        }
        open.push_back(piece);
    }
    // Refine only what could still hold a distance larger than the best found by > tolerance.
    std::size_t refined = 0;
    double unresolved = 0;  // the largest bound left when the budget ran out
    while (!open.empty()) {
        const Piece piece = open.back();
        open.pop_back();
        const double bound = upper_bound(piece, target);
        if (bound <= lower + tolerance) {
            continue;
        }
        if (++refined > kRefinementBudget) {
            unresolved = std::max(unresolved, bound);
            continue;
        }
        Piece mid;
        for (int k = 0; k < 3; ++k) {
            mid.corner[k] = 0.5 * (piece.corner[k] + piece.corner[(k + 1) % 3]);
            const SurfacePoint found = target.bvh.closest_point(mid.corner[k]);
            mid.distance[k] = found.distance;
            mid.face[k] = found.face;
            consider(mid.corner[k], mid.distance[k]);
        }
        // Corner k's child: k, mid(k, k+1), mid(k+2, k); and the middle triangle.
        for (int k = 0; k < 3; ++k) {
            Piece child;
            child.corner[0] = piece.corner[k];
            child.distance[0] = piece.distance[k];
            child.face[0] = piece.face[k];
            child.corner[1] = mid.corner[k];
            child.distance[1] = mid.distance[k];
            child.face[1] = mid.face[k];
            child.corner[2] = mid.corner[(k + 2) % 3];
            child.distance[2] = mid.distance[(k + 2) % 3];
            child.face[2] = mid.face[(k + 2) % 3];
            open.push_back(child);
        }
        open.push_back(mid);
    }
    result.hausdorff = std::max(lower, 0.0);
    result.hausdorff_upper_bound = std::max(result.hausdorff + tolerance, unresolved);
}

// A face's share of the mean and RMS integrals and of their bounds: Σ over its pieces of area·d,
// area·d², area·r, area·r² (d the distance of a piece's centroid, r its radius), and its area.
struct FaceIntegrals {
    double integral = 0;
    double integral2 = 0;
    double mean_bound = 0;
    double rms_bound2 = 0;
    double area = 0;
};

FaceIntegrals face_integrals(const TriangleMesh& from, Eigen::Index f, const TriangleBvh& to,
                             double length) {
    FaceIntegrals sums;
    const detail::Triangle t(from, f);
    const double longest =
        std::max({(t.x[1] - t.x[0]).norm(), (t.x[2] - t.x[1]).norm(), (t.x[0] - t.x[2]).norm()});
    const int splits = std::clamp(static_cast<int>(std::ceil(longest / length)), 1, 256);
    const double piece_area = t.area() / (static_cast<double>(splits) * splits);
    // Split into splits² similar triangles (upward and downward) and use their centroids.
    for (int i = 0; i < splits; ++i) {
        for (int j = 0; i + j < splits; ++j) {
            for (int flip = 0; flip < 2 && (flip == 0 || i + j + 1 < splits); ++flip) {
                Eigen::Vector3d corner[3];
                const double s = splits;
                const auto at = [&](double u, double v) {
                    return t.x[0] + (u / s) * (t.x[1] - t.x[0]) + (v / s) * (t.x[2] - t.x[0]);
                };
                if (flip == 0) {
                    corner[0] = at(i, j);
                    corner[1] = at(i + 1, j);
                    corner[2] = at(i, j + 1);
                } else {
                    corner[0] = at(i + 1, j);
                    corner[1] = at(i + 1, j + 1);
                    corner[2] = at(i, j + 1);
                }
                const Eigen::Vector3d centroid = (corner[0] + corner[1] + corner[2]) / 3;
                const double radius =
                    std::max({(corner[0] - centroid).norm(), (corner[1] - centroid).norm(),
                              (corner[2] - centroid).norm()});
                const double d = to.distance(centroid);
                sums.integral += piece_area * d;
                sums.integral2 += piece_area * d * d;
                sums.mean_bound += piece_area * radius;
                sums.rms_bound2 += piece_area * radius * radius;
            }
        }
    }
    sums.area = t.area();
    return sums;
}

// The faces' integrals are computed in parallel and added in face order: the same bits for any
// thread count.
void one_sided_mean(const TriangleMesh& from, const TriangleBvh& to, double length,
                    OneSidedDistance& result) {
    std::vector<FaceIntegrals> faces(static_cast<std::size_t>(from.F.rows()));
#pragma omp parallel for schedule(dynamic, 64)
    for (Eigen::Index f = 0; f < from.F.rows(); ++f) {
        faces[static_cast<std::size_t>(f)] = face_integrals(from, f, to, length);
    }
    FaceIntegrals total;
    for (const FaceIntegrals& face : faces) {
        total.integral += face.integral;
        total.integral2 += face.integral2;
        total.mean_bound += face.mean_bound;
        total.rms_bound2 += face.rms_bound2;
        total.area += face.area;
    }
    result.area = total.area;
    if (total.area > 0) {
        result.mean = total.integral / total.area;
        result.rms = std::sqrt(total.integral2 / total.area);
        result.mean_error_bound = total.mean_bound / total.area;
        result.rms_error_bound = std::sqrt(total.rms_bound2 / total.area);
    }
}

}  // namespace

SurfaceDistances surface_distances(const TriangleMesh& A, const TriangleMesh& B,
                                   const SurfaceDistanceOptions& options) {
    for (const TriangleMesh* mesh : {&A, &B}) {
        detail::require_valid_mesh(*mesh, "surface_distances");
        if (mesh->F.rows() == 0) {
            throw InvalidInput("surface_distances: a mesh has no faces");
        }
    }
    if (!detail::finite_at_least(options.hausdorff_tolerance, 0) ||
        !detail::finite_at_least(options.quadrature_length, 0)) {
        throw InvalidInput("surface_distances: tolerances must be finite and non-negative");
    }
    const double scale = std::max(bounding_box_diagonal(A), bounding_box_diagonal(B));
    double tolerance = options.hausdorff_tolerance > 0 ? options.hausdorff_tolerance : 1e-4 * scale;
    double length = options.quadrature_length > 0
                        ? options.quadrature_length
                        : 0.5 * std::min(mean_edge_length(A), mean_edge_length(B));
    if (!(tolerance > 0)) {
        tolerance = 1e-12;  // both meshes are single points
    }
    if (!(length > 0)) {
        length = std::max(scale, 1e-12);
    }
    const TriangleBvh bvh_a(A);
    const TriangleBvh bvh_b(B);
    SurfaceDistances result;
    one_sided_hausdorff(A, Target{B, bvh_b}, tolerance, result.a_to_b);
    one_sided_hausdorff(B, Target{A, bvh_a}, tolerance, result.b_to_a);
    one_sided_mean(A, bvh_b, length, result.a_to_b);
    one_sided_mean(B, bvh_a, length, result.b_to_a);
    result.hausdorff = std::max(result.a_to_b.hausdorff, result.b_to_a.hausdorff);
    result.hausdorff_upper_bound =
        std::max(result.a_to_b.hausdorff_upper_bound, result.b_to_a.hausdorff_upper_bound);
    const double total_area = result.a_to_b.area + result.b_to_a.area;
    if (total_area > 0) {
        result.mean =
            (result.a_to_b.mean * result.a_to_b.area + result.b_to_a.mean * result.b_to_a.area) /
            total_area;
        result.rms = std::sqrt((result.a_to_b.rms * result.a_to_b.rms * result.a_to_b.area +
                                result.b_to_a.rms * result.b_to_a.rms * result.b_to_a.area) /
                               total_area);
    }
    return result;
}

}  // namespace genflow
