// SPDX-License-Identifier: MIT
#include "matching/similarity_scale.h"

#include <cmath>

#include "genflow/mesh/edges.h"
#include "genflow/operators/area.h"
#include "genflow/operators/volume.h"

namespace genflow::detail {

double boundary_length(const TriangleMesh& mesh) {
    const Eigen::MatrixX2i edges = boundary_edges(mesh.F);
    double length = 0;
    for (Eigen::Index e = 0; e < edges.rows(); ++e) {
        length += (mesh.V.row(edges(e, 0)) - mesh.V.row(edges(e, 1))).norm();
    }
    return length;
}

double capped_volume(const TriangleMesh& mesh) {
    // The cone over a boundary edge to a point c encloses no volume about c, so the volume of
    // the capped mesh is the mesh's own about c.
    const Eigen::MatrixX2i edges = boundary_edges(mesh.F);
    if (edges.rows() == 0) {
        return std::abs(enclosed_volume(mesh));
    }
    Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
    for (Eigen::Index e = 0; e < edges.rows(); ++e) {
        centre += mesh.V.row(edges(e, 0)) + mesh.V.row(edges(e, 1));
    }
    centre /= static_cast<double>(2 * edges.rows());
    TriangleMesh about_centre = mesh;
    about_centre.V.rowwise() -= centre;
    return std::abs(enclosed_volume(about_centre));
}

std::optional<double> volume_scale_where_areas_mislead(const TriangleMesh& from,
                                                       const TriangleMesh& to, double area_scale) {
    const double from_volume = capped_volume(from);
    const double to_volume = capped_volume(to);
    if (!(from_volume > 0) || !(to_volume > 0) || !std::isfinite(from_volume) ||
        !std::isfinite(to_volume)) {
        return std::nullopt;
    }
    const double volume_scale = std::cbrt(to_volume / from_volume);
    if (!(area_scale > volume_scale * (1 + kAreaVolumeTolerance) ||
          area_scale < volume_scale / (1 + kAreaVolumeTolerance))) {
        return std::nullopt;
    }
    // Only now the boundaries: an area that agrees with the volume stands whatever they are.
    for (const TriangleMesh* mesh : {&from, &to}) {
        if (boundary_length(*mesh) > kShortBoundary * std::sqrt(surface_area(*mesh))) {
            return std::nullopt;
        }
    }
    return volume_scale;
}

}  // namespace genflow::detail
