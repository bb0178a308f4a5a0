// SPDX-License-Identifier: MIT
#include "genflow/evaluation/geodesic_error.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/operators/area.h"
#include "operators/triangle.h"
#include "spatial/surface_paths.h"

namespace genflow {

struct GeodesicErrorMeasure::Impl {
    TriangleMesh target;
    detail::ChordGraph edges;
    double unit = 0;
};

GeodesicErrorMeasure::GeodesicErrorMeasure(const TriangleMesh& target)
    : impl_(std::make_unique<Impl>()) {
    detail::require_valid_mesh(target, "GeodesicErrorMeasure");
    if (target.F.rows() == 0) {
        throw InvalidInput("GeodesicErrorMeasure: the target has no faces");
    }
    const double area = surface_area(target);
    if (!(area > 0) || !std::isfinite(area)) {
        throw InvalidInput("GeodesicErrorMeasure: the target has zero area");
    }
    impl_->target = target;
    impl_->edges = detail::chord_graph(target, 1);
    impl_->unit = std::sqrt(area);
}

GeodesicErrorMeasure::~GeodesicErrorMeasure() = default;
GeodesicErrorMeasure::GeodesicErrorMeasure(GeodesicErrorMeasure&&) noexcept = default;
GeodesicErrorMeasure& GeodesicErrorMeasure::operator=(GeodesicErrorMeasure&&) noexcept = default;

double GeodesicErrorMeasure::unit() const {
    return impl_->unit;
}

namespace {

// The reference points grouped by their true vertex: one Dijkstra per group.
std::vector<std::vector<std::size_t>> group_by_vertex(const std::vector<Eigen::Index>& truth,
                                                      Eigen::Index vertices) {
    std::vector<std::vector<std::size_t>> by_vertex(static_cast<std::size_t>(vertices));
    for (std::size_t k = 0; k < truth.size(); ++k) {
        by_vertex[static_cast<std::size_t>(truth[k])].push_back(k);
    }
    std::erase_if(by_vertex, [](const auto& group) { return group.empty(); });
    return by_vertex;
}

}  // namespace

GeodesicErrors GeodesicErrorMeasure::errors(const std::vector<SurfacePoint>& mapped,
                                            const std::vector<Eigen::Index>& truth) const {
    const TriangleMesh& target = impl_->target;
    if (mapped.size() != truth.size()) {
        throw InvalidInput("GeodesicErrorMeasure::errors: " + std::to_string(mapped.size()) +
                           " mapped points for " + std::to_string(truth.size()) +
                           " reference points");
    }
    for (std::size_t k = 0; k < truth.size(); ++k) {
        if (truth[k] < 0 || truth[k] >= target.V.rows() || mapped[k].face < 0 ||
            mapped[k].face >= target.F.rows()) {
            throw InvalidInput("GeodesicErrorMeasure::errors: reference point " +
                               std::to_string(k) + " has a vertex or face out of range");
        }
    }
    const std::vector<std::vector<std::size_t>> groups = group_by_vertex(truth, target.V.rows());
    GeodesicErrors result{Eigen::VectorXd(static_cast<Eigen::Index>(truth.size())),
                          Eigen::VectorXd(static_cast<Eigen::Index>(truth.size()))};
    const double unit = impl_->unit;
#pragma omp parallel for schedule(dynamic, 16)
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const std::vector<std::size_t>& group = groups[g];
        std::vector<Eigen::Index> corners;
        for (const std::size_t k : group) {
            for (int c = 0; c < 3; ++c) {
                corners.push_back(target.F(mapped[k].face, c));
            }
        }
        const std::vector<double> path =
            detail::path_lengths_to(impl_->edges, truth[group.front()], corners);
        for (std::size_t i = 0; i < group.size(); ++i) {
            const std::size_t k = group[i];
            const Eigen::Vector3d& b = mapped[k].barycentric;
            Eigen::RowVector3d point = Eigen::RowVector3d::Zero();
            for (int c = 0; c < 3; ++c) {
                point += b(c) * target.V.row(corners[3 * i + static_cast<std::size_t>(c)]);
            }
            double to_point = detail::kUnreachable;
            double nearest_corner = detail::kUnreachable;
            double to_vertex = detail::kUnreachable;
            for (int c = 0; c < 3; ++c) {
                const std::size_t at = 3 * i + static_cast<std::size_t>(c);
                const double segment = (point - target.V.row(corners[at])).norm();
                to_point = std::min(to_point, path[at] + segment);
                if (segment < nearest_corner) {
                    nearest_corner = segment;
                    to_vertex = path[at];
                }
            }
            const auto row = static_cast<Eigen::Index>(k);
            result.to_point(row) = std::isfinite(to_point) ? to_point / unit : 1.0;
            result.to_vertex(row) = std::isfinite(to_vertex) ? to_vertex / unit : 1.0;
        }
    }
    return result;
}

GeodesicErrors GeodesicErrorMeasure::errors_at(const std::vector<SurfacePoint>& map,
                                               const std::vector<Eigen::Index>& from_reference,
                                               const std::vector<Eigen::Index>& truth) const {
    std::vector<SurfacePoint> mapped;
    mapped.reserve(from_reference.size());
    for (const Eigen::Index v : from_reference) {
        if (v < 0 || static_cast<std::size_t>(v) >= map.size()) {
            throw InvalidInput("GeodesicErrorMeasure::errors_at: template vertex " +
                               std::to_string(v) + " is out of range of a map of " +
                               std::to_string(map.size()) + " vertices");
        }
        mapped.push_back(map[static_cast<std::size_t>(v)]);
    }
    return errors(mapped, truth);
}

}  // namespace genflow
