// SPDX-License-Identifier: MIT
// The error measure of the public correspondence benchmarks (FAUST_r, SCAPE_r, SHREC'19_r and
// the tables of the papers that report on them): for each reference point, the geodesic
// distance on the target between where a map put it and where it belongs, over √area of the
// target. Geodesics are shortest paths along the mesh's edges (Dijkstra), as in the public
// evaluation code: 5–9 % longer than exact geodesics on those meshes, so figures compare with
// the published ones.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "genflow/mesh.h"
#include "genflow/spatial/closest_point.h"

namespace genflow {

/// Per reference point, how far a map put it from where it belongs, in units of √area of the
/// target (the published tables print these × 100).
struct GeodesicErrors {
    /// The map's point as it is: the shortest edge path from the true vertex to a corner of the
    /// point's face, plus the straight segment from that corner to the point.
    Eigen::VectorXd to_point;
    /// The map's point snapped to the nearest corner of its face, then the edge path: what a
    /// vertex-to-vertex map, as the published methods produce, would be measured at.
    Eigen::VectorXd to_vertex;
};

/// The target's edge graph and unit, built once and used for every pair that ends on it.
class GeodesicErrorMeasure {
public:
    /// \throws InvalidInput if `target` has no face, an index out of range, a non-finite
    ///         coordinate or zero area.
    explicit GeodesicErrorMeasure(const TriangleMesh& target);
    ~GeodesicErrorMeasure();
    GeodesicErrorMeasure(GeodesicErrorMeasure&&) noexcept;
    GeodesicErrorMeasure& operator=(GeodesicErrorMeasure&&) noexcept;

    /// `mapped[k]`: where a map put reference point k on the target (its face and barycentric
    /// coordinates are used); `truth[k]`: the target's vertex where it belongs. Each distinct
    /// true vertex runs one Dijkstra that stops at the corners it needs, so small errors are
    /// cheap. Unreachable points (another component) count as √area × 1 each: an error no map
    /// of a connected shape can exceed by much, and finite. Uses the cores when OpenMP is there.
    /// \throws InvalidInput if the sizes differ, or a face or vertex index is out of range.
    [[nodiscard]] GeodesicErrors errors(const std::vector<SurfacePoint>& mapped,
                                        const std::vector<Eigen::Index>& truth) const;

    /// The errors of a map of every template vertex (`map[v]`: where it put template vertex v)
    /// at the reference points: template vertex `from_reference[k]` belongs at target vertex
    /// `truth[k]`. The benchmarks' measure of a whole map.
    /// \throws InvalidInput as errors(), or if a template vertex is out of range of `map`.
    [[nodiscard]] GeodesicErrors errors_at(const std::vector<SurfacePoint>& map,
                                           const std::vector<Eigen::Index>& from_reference,
                                           const std::vector<Eigen::Index>& truth) const;

    /// √area of the target, the unit of the errors.
    [[nodiscard]] double unit() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace genflow
