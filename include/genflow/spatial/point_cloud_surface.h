// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

#include "genflow/mesh.h"

namespace genflow {

/// Parameters of `point_cloud_surface()`.
struct PointCloudSurfaceOptions {
    /// Neighbours of each point its local triangulation is built from. Twelve reach two rings
    /// of a regular sampling (6 + 6), enough for the Delaunay triangles around a point to be
    /// decided by the points they could contain; more cost time and smooth the tangent planes.
    int neighbours = 12;
};

/// A triangle mesh on the points of a point cloud (#P×3): vertex i is point i, so the mesh's
/// vertex indices are the cloud's. It lets everything that needs a surface (the barycentric
/// masses that weigh d_H, closest points, the Laplacian of the intrinsic guidance) take a point
/// cloud as it takes a mesh.
///
/// The rule, after the local triangulations of Sharp and Crane's point-cloud Laplacian (2020):
/// 1. Each point's fan is the Delaunay triangles around it among its nearest neighbours, laid
///    out on its tangent plane (the plane of least variance of the point and its nearest six)
///    each at its own distance. A triangle is in the fan only if its circumcentre lies within
///    the farthest neighbour's distance, so a point on a scan's border closes no triangle
///    across the open side.
/// 2. The fans' triangles are offered to the mesh held by more fans first (more tangent planes
///    agree on them), then the smaller circumcircle first. One is kept only if none of its
///    edges already has two faces or a face it would fold onto (the two diagonals of a
///    quadrilateral; told in the tangent plane at the edge, so that noise along the normal does
///    not make a sharp bend look like a fold): the mesh is edge-manifold.
/// 3. The faces are oriented across shared edges, better-ranked first; where they cannot agree
///    (faces bridging the two sides of a thin part into a Möbius band) the lower-ranked are
///    left out. Each component then takes the side of its corners' normals, oriented along a
///    minimum spanning tree of the neighbours (Hoppe et al. 1992), and the whole the side
///    that encloses a positive volume (outward, on a closed or nearly closed surface).
/// 4. A gap of three or four boundary edges, where the fans did not agree, is closed (a face,
///    or two along the shorter diagonal that is not an edge yet), until none is left.
///
/// The mesh may have small holes and non-manifold vertices where the sampling is too coarse
/// for the surface's curvature (a finger two or three points across); repair_surface(), which
/// match() applies to every target, splits those. Points at the coordinates of an earlier point
/// are left unreferenced, as are points no face keeps (isolated outliers).
///
/// \throws InvalidInput if there are fewer than 4 points, a coordinate is not finite,
///         `neighbours` < 4, or no face can be built.
[[nodiscard]] TriangleMesh point_cloud_surface(const Eigen::MatrixX3d& points,
                                               const PointCloudSurfaceOptions& options = {});

/// The same with the points' normals (#P×3, any length, pointing out of the surface, as a
/// scanner gives them). They settle what positions alone cannot where two sheets face each
/// other across a gap narrower than the sampling (an arm against the torso, the thighs): a
/// neighbour whose normal points against a point's is on the other sheet and is left out of
/// its fan, so no face bridges the gap. Each tangent plane is then the one square to the point's
/// normal, and the faces take the normals' side.
/// \throws InvalidInput as above, or if there is not one normal per point or a normal is zero
///         or not finite.
[[nodiscard]] TriangleMesh point_cloud_surface(const Eigen::MatrixX3d& points,
                                               const Eigen::MatrixX3d& normals,
                                               const PointCloudSurfaceOptions& options = {});

}  // namespace genflow
