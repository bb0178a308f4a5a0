// SPDX-License-Identifier: MIT
#include "matching/spectral_descriptors.h"

#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/operators/heat_kernel_signature.h"
#include "genflow/operators/laplacian_eigenbasis.h"
#include "matching/analysis_store.h"
#include "matching/functional_map.h"

namespace genflow::detail {

namespace {

// Enough for eigenfunction_descriptors() to choose from.
constexpr Eigen::Index kKeptFunctions = 64;

// The sizes ZoomOut starts from (SpectralDescriptors::eigenfunction_descriptors()).
constexpr std::array<Eigen::Index, 4> kZoomOutFirstSizes{4, 6, 8, 10};

// What the spectral view keeps of one coarse mesh, for its vertices with area (those without
// have no signature and no eigenfunction values).
struct CoarseSpectrum {
    std::vector<Eigen::Index> vertex;
    Eigen::MatrixXd log_signature;
    Eigen::MatrixXd functions;  // non-constant, ascending, times sqrt(area) (dimensionless)
    Eigen::VectorXd masses;     // over the area (they sum to at most 1)
    Eigen::VectorXd values;     // of `functions`, times the area (dimensionless)
};

CoarseSpectrum coarse_spectrum(const TriangleMesh& coarse) {
    const LaplacianEigenbasis basis = laplacian_eigenbasis(coarse);
    const Eigen::MatrixXd signature = heat_kernel_signature(basis);
    CoarseSpectrum result;
    for (Eigen::Index i = 0; i < signature.rows(); ++i) {
        if ((signature.row(i).array() > 0).all()) {
            result.vertex.push_back(i);
        }
    }
    const Eigen::Index count = std::min(kKeptFunctions, basis.values.size() - 1);
    const auto kept = Eigen::seqN(1, count);
    result.log_signature = signature(result.vertex, Eigen::all).array().log();
    // In units of the mesh's own area, so that the two meshes' functions are comparable
    // whatever the ratio of their sizes (issue 5: inputs may differ by any scale): M-orthonormal
    // functions are of size 1/sqrt(area), and a map between functions of different sizes has
    // singular values, and ZoomOut distances, scaled by that ratio.
    const double area = basis.masses.sum();
    result.functions = std::sqrt(area) * basis.functions(result.vertex, kept);
    result.masses = basis.masses(result.vertex) / area;
    result.values = basis.values(kept) * area;
    return result;
}

// A mesh coarsened for the spectral view, and that view.
struct CoarseView {
    CoarseMesh coarse;
    CoarseSpectrum spectrum;
};

CoarseView coarse_view(const TriangleMesh& mesh, Eigen::Index vertices) {
    CoarseMesh coarse = coarsen(mesh, vertices);
    CoarseSpectrum spectrum = coarse_spectrum(coarse.mesh);
    return {std::move(coarse), std::move(spectrum)};
}

// 1 for an orthogonal map; lower as the map loses functions (SpectralDescriptors::
// map_consistency()).
double mean_singular_value(const Eigen::MatrixXd& map) {
    return Eigen::JacobiSVD<Eigen::MatrixXd>(map).singularValues().mean();
}

}  // namespace

SpectralDescriptors::SpectralDescriptors(const TriangleMesh& template_mesh,
                                         const TriangleMesh& target,
                                         const std::shared_ptr<TemplateCache>& template_cache,
                                         Eigen::Index vertices)
    : template_vertices_(template_mesh.V.rows()),
      template_points_(Eigen::MatrixX3d(0, 3)),
      target_points_(Eigen::MatrixX3d(0, 3)) {
    TwoAnalyses<CoarseView> views = analysed_side_by_side<CoarseView>(
        template_cache, "spectral view", template_mesh, target, vertices,
        [&](const TriangleMesh& mesh) { return coarse_view(mesh, vertices); });
    const CoarseView& template_view = *views.of_template;
    const CoarseSpectrum& from = template_view.spectrum;
    const CoarseMesh& coarse_target = views.of_target.coarse;
    CoarseSpectrum& to = views.of_target.spectrum;
    if (from.vertex.empty() || to.vertex.empty()) {
        throw InvalidInput("SpectralDescriptors: a mesh has no vertex with area");
    }
    for (const Eigen::Index k : from.vertex) {
        template_vertex_.push_back(template_view.coarse.fine_vertex[static_cast<std::size_t>(k)]);
    }
    template_points_ = PointIndex(template_mesh.V(template_vertex_, Eigen::all));
    target_positions_ = coarse_target.mesh.V(to.vertex, Eigen::all);
    target_points_ = PointIndex(target_positions_);
    template_log_signature_ = from.log_signature;
    target_log_signature_ = std::move(to.log_signature);
    template_functions_ = from.functions;
    target_functions_ = std::move(to.functions);
    template_masses_ = from.masses;
    target_values_ = std::move(to.values);
}

std::vector<Eigen::Index> SpectralDescriptors::nearest_target_rows(
    const Eigen::MatrixX3d& deformed) const {
    if (deformed.rows() != template_vertices_) {
        throw InvalidInput("SpectralDescriptors: the deformed template has " +
                           std::to_string(deformed.rows()) + " vertices, not " +
                           std::to_string(template_vertices_));
    }
    std::vector<Eigen::Index> nearest(template_vertex_.size());
    for (std::size_t k = 0; k < template_vertex_.size(); ++k) {
        nearest[k] = target_points_.nearest(deformed.row(template_vertex_[k]).transpose()).first;
    }
    return nearest;
}

double SpectralDescriptors::discrepancy(const Eigen::MatrixX3d& deformed) const {
    return signature_discrepancy(nearest_target_rows(deformed));
}

double SpectralDescriptors::signature_discrepancy(
    const std::vector<Eigen::Index>& correspondence) const {
    std::vector<double> squared(correspondence.size());
    for (std::size_t k = 0; k < correspondence.size(); ++k) {
        squared[k] = (template_log_signature_.row(static_cast<Eigen::Index>(k)) -
                      target_log_signature_.row(correspondence[k]))
                         .squaredNorm();
    }
    const auto middle = squared.begin() + static_cast<std::ptrdiff_t>(squared.size() / 2);
    std::nth_element(squared.begin(), middle, squared.end());
    return *middle;
}

Eigen::Index SpectralDescriptors::function_count(int functions) const {
    return std::min({static_cast<Eigen::Index>(std::max(functions, 1)), template_functions_.cols(),
                     target_functions_.cols()});
}

double SpectralDescriptors::map_consistency(const Eigen::MatrixX3d& deformed, int functions) const {
    const std::vector<Eigen::Index> correspondence = nearest_target_rows(deformed);
    const Eigen::Index count = function_count(functions);
    return mean_singular_value(fitted_functional_map(template_functions_, template_masses_,
                                                     target_functions_, correspondence, count));
}

namespace {

// Each point's row of `values`, taken at the nearest point of `index`.
Eigen::MatrixXd at_nearest(const Eigen::MatrixX3d& points, const PointIndex& index,
                           const Eigen::MatrixXd& values) {
    Eigen::MatrixXd result(points.rows(), values.cols());
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
        result.row(i) = values.row(index.nearest(points.row(i).transpose()).first);
    }
    return result;
}

}  // namespace

PointDescriptors SpectralDescriptors::signature_descriptors(const Eigen::MatrixX3d& template_points,
                                                            const Eigen::MatrixX3d& target_points,
                                                            double length) const {
    const Eigen::RowVectorXd mean = template_log_signature_.colwise().mean();
    const Eigen::RowVectorXd deviation =
        (template_log_signature_.rowwise() - mean).array().square().colwise().mean().sqrt();
    const auto times = static_cast<double>(template_log_signature_.cols());
    // A time at which every template point has the same signature carries no information.
    const Eigen::RowVectorXd scale =
        (deviation.array() > 0).select(length / std::sqrt(times) / deviation.array(), 0.0);
    const auto normalized = [&](const Eigen::MatrixXd& log_signature) {
        return Eigen::MatrixXd((log_signature.rowwise() - mean).array().rowwise() * scale.array());
    };
    return {at_nearest(template_points, template_points_, normalized(template_log_signature_)),
            at_nearest(target_points, target_points_, normalized(target_log_signature_))};
}

std::vector<Eigen::Index> SpectralDescriptors::zoom_out(std::vector<Eigen::Index> correspondence,
                                                        Eigen::Index first,
                                                        Eigen::Index count) const {
    return detail::zoom_out(template_functions_, template_masses_, target_functions_,
                            function_weights(count), std::move(correspondence), first, count);
}

Eigen::RowVectorXd SpectralDescriptors::function_weights(Eigen::Index count) const {
    return embedding_weights(target_values_.head(count));
}

PointDescriptors SpectralDescriptors::eigenfunction_descriptors(
    const std::vector<Eigen::MatrixX3d>& placements, const Eigen::MatrixX3d& template_points,
    const Eigen::MatrixX3d& target_points, double length, int functions) const {
    if (placements.empty()) {
        throw InvalidInput("SpectralDescriptors: no placement to estimate the map from");
    }
    const Eigen::Index count = function_count(functions);
    struct Candidate {
        Eigen::MatrixXd map;
        double singular_value = 0;
        double moved = 0;  // summed distance between where the placement and the map put points
        double discrepancy = 0;  // of the signatures over the map's correspondence
    };
    std::vector<Candidate> candidates;
    for (const Eigen::MatrixX3d& deformed : placements) {
        const std::vector<Eigen::Index> start = nearest_target_rows(deformed);
        for (const Eigen::Index first : kZoomOutFirstSizes) {
            const std::vector<Eigen::Index> end = zoom_out(start, first, count);
            Candidate candidate;
            candidate.map = fitted_functional_map(template_functions_, template_masses_,
                                                  target_functions_, end, count);
            candidate.singular_value = mean_singular_value(candidate.map);
            candidate.discrepancy = signature_discrepancy(end);
            for (std::size_t k = 0; k < end.size(); ++k) {
                candidate.moved +=
                    (target_positions_.row(end[k]) - target_positions_.row(start[k])).norm();
            }
            candidates.push_back(std::move(candidate));
        }
    }
    // Each map is rated on its own correspondence as a match's intrinsic disagreement is,
    // with the orthogonality less the motion of the placement's points (see the header: neither
    // the signatures nor the motion alone tell every symmetric map from the right one).
    const Eigen::Index points = static_cast<Eigen::Index>(template_vertex_.size());
    const double per_point =
        1 /
        (static_cast<double>(points) *
         (target_positions_.colwise().maxCoeff() - target_positions_.colwise().minCoeff()).norm());
    const auto disagreement = [&](const Candidate& candidate) {
        const double consistency = candidate.singular_value - per_point * candidate.moved;
        return consistency > 0 ? candidate.discrepancy / consistency
                               : std::numeric_limits<double>::infinity();
    };
    const Candidate* kept = &candidates.front();
    for (const Candidate& candidate : candidates) {
        if (disagreement(candidate) < disagreement(*kept)) {
            kept = &candidate;
        }
    }
    const Eigen::MatrixXd& best_map = kept->map;
    const Eigen::RowVectorXd weight = function_weights(count);
    const Eigen::MatrixXd target = target_functions_.leftCols(count) * weight.asDiagonal();
    const Eigen::MatrixXd mapped =
        template_functions_.leftCols(count) * best_map * weight.asDiagonal();
    const double spread = std::sqrt((target.rowwise() - target.colwise().mean()).squaredNorm() /
                                    static_cast<double>(target.rows()));
    const double scale = spread > 0 ? length / spread : 0;
    return {at_nearest(template_points, template_points_, scale * mapped),
            at_nearest(target_points, target_points_, scale * target)};
}

}  // namespace genflow::detail
