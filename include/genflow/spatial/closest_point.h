// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "genflow/mesh.h"

namespace genflow {

/// The point of a triangle (a, b, c) nearest to p, as barycentric coordinates (w_a, w_b, w_c),
/// all ≥ 0 and summing to 1. Exact up to rounding for any triangle, degenerate ones (segments,
/// points) included (Ericson, Real-Time Collision Detection, §5.1.5, region by region).
[[nodiscard]] Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p,
                                                        const Eigen::Vector3d& a,
                                                        const Eigen::Vector3d& b,
                                                        const Eigen::Vector3d& c);

/// Where a query landed on a mesh.
struct SurfacePoint {
    Eigen::Index face = -1;       ///< the face holding the closest point
    Eigen::Vector3d barycentric;  ///< its coordinates on the face's corners F(face, 0..2)
    Eigen::Vector3d point;        ///< the closest point itself
    double distance = 0;          ///< |query − point|
};

/// The points' positions (SurfacePoint::point), a row each.
[[nodiscard]] Eigen::MatrixX3d positions_of(const std::vector<SurfacePoint>& points);

/// Closest-point queries on a fixed triangle mesh through a bounding-volume hierarchy (axis-
/// aligned boxes, median split, best-first traversal): O(log #F) per query on reasonable
/// meshes, exact (the same answer as a brute-force scan over all faces, up to ties).
///
/// Build once, query many times; const queries may run concurrently.
class TriangleBvh {
public:
    /// \throws InvalidInput if the mesh has no face, indexes outside V or holds a non-finite
    ///         coordinate.
    explicit TriangleBvh(const TriangleMesh& mesh);
    ~TriangleBvh();
    TriangleBvh(TriangleBvh&&) noexcept;
    TriangleBvh& operator=(TriangleBvh&&) noexcept;

    /// The surface point nearest to `query`.
    [[nodiscard]] SurfacePoint closest_point(const Eigen::Vector3d& query) const;

    /// Distance from `query` to the surface.
    [[nodiscard]] double distance(const Eigen::Vector3d& query) const {
        return closest_point(query).distance;
    }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace genflow
