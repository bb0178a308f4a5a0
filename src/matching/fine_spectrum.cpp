// SPDX-License-Identifier: MIT
#include "matching/fine_spectrum.h"

#include <algorithm>
#include <string>

#include "genflow/exceptions.h"
#include "matching/functional_map.h"
#include "matching/side_by_side.h"

namespace genflow::detail {

FineSpectrum::FineSpectrum(const TriangleMesh& template_rest, const TriangleMesh& target,
                           int functions)
    : template_basis_(laplacian_eigenbasis(template_rest, functions + 1)),
      target_basis_(laplacian_eigenbasis(target, functions + 1)),
      target_points_(target.V) {}

VertexMap FineSpectrum::zoomed_out_map(const Eigen::MatrixX3d& deformed,
                                       Eigen::Index first_size) const {
    return zoomed_out_from(nearest_target_vertices(deformed), first_size);
}

std::vector<VertexMap> FineSpectrum::zoomed_out_maps(const Eigen::MatrixX3d& deformed) const {
    // Every ZoomOut starts from the same correspondence. They are independent, and each too
    // small to keep both cores busy in its matrix products.
    const std::vector<Eigen::Index> correspondence = nearest_target_vertices(deformed);
    std::vector<VertexMap> maps(kFineMapFirstSizes.size());
    run_side_by_side(maps.size(), [&](std::size_t k) {
        maps[k] = zoomed_out_from(correspondence, kFineMapFirstSizes[k]);
    });
    return maps;
}

std::vector<Eigen::Index> FineSpectrum::nearest_target_vertices(
    const Eigen::MatrixX3d& deformed) const {
    if (deformed.rows() != template_basis_.functions.rows()) {
        throw InvalidInput("zoomed_out_map: the deformed template has " +
                           std::to_string(deformed.rows()) + " vertices, not " +
                           std::to_string(template_basis_.functions.rows()));
    }
    std::vector<Eigen::Index> correspondence(static_cast<std::size_t>(deformed.rows()));
    for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
        correspondence[static_cast<std::size_t>(i)] =
            target_points_.nearest(deformed.row(i).transpose()).first;
    }
    return correspondence;
}

VertexMap FineSpectrum::zoomed_out_from(std::vector<Eigen::Index> correspondence,
                                        Eigen::Index first_size) const {
    if (first_size < 1) {
        throw InvalidInput("zoomed_out_map: ZoomOut must start from at least one function, not " +
                           std::to_string(first_size));
    }
    VertexMap map;
    map.template_masses = template_basis_.masses;
    // Without the constant function.
    map.functions = std::min(template_basis_.values.size(), target_basis_.values.size()) - 1;
    if (map.functions < 1) {
        map.functions = 0;
        return map;
    }
    const auto count = map.functions;
    constexpr Eigen::Index kStep = 5;
    map.target_vertex =
        zoom_out(template_basis_.functions.middleCols(1, count), template_basis_.masses,
                 target_basis_.functions.middleCols(1, count),
                 embedding_weights(target_basis_.values.segment(1, count)),
                 std::move(correspondence), first_size, count, kStep);
    return map;
}

}  // namespace genflow::detail
