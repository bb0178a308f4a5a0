// SPDX-License-Identifier: MIT
#include "genflow/spatial/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/spatial/closest_point.h"
#include "one_sided_hausdorff.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

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

void store_hausdorff(const detail::OneSidedHausdorff& found, OneSidedDistance& result) {
    result.hausdorff = found.distance;
    result.hausdorff_upper_bound = found.upper_bound;
    result.farthest_point = found.farthest_point;
}

// The two meshes' trees, built side by side (a build is one thread's work). An exception may
// not leave an OpenMP block, so it is carried out of it.
std::pair<TriangleBvh, TriangleBvh> build_both(const TriangleMesh& A, const TriangleMesh& B) {
    std::unique_ptr<TriangleBvh> trees[2];
    std::exception_ptr failure[2];
#pragma omp parallel for schedule(static, 1) num_threads(2)
    for (int k = 0; k < 2; ++k) {
        try {
            trees[k] = std::make_unique<TriangleBvh>(k == 0 ? A : B);
        } catch (...) {
            failure[k] = std::current_exception();
        }
    }
    for (const std::exception_ptr& f : failure) {
        if (f) {
            std::rethrow_exception(f);
        }
    }
    return {std::move(*trees[0]), std::move(*trees[1])};
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
    const auto [bvh_a, bvh_b] = build_both(A, B);
    SurfaceDistances result;
    store_hausdorff(detail::one_sided_hausdorff(A, B, bvh_b, tolerance), result.a_to_b);
    store_hausdorff(detail::one_sided_hausdorff(B, A, bvh_a, tolerance), result.b_to_a);
    if (options.mean_and_rms) {
        one_sided_mean(A, bvh_b, length, result.a_to_b);
        one_sided_mean(B, bvh_a, length, result.b_to_a);
    }
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
