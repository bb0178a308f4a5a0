// SPDX-License-Identifier: MIT
#include "matching/intrinsic_shape.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "genflow/operators/area.h"
#include "genflow/operators/laplacian_eigenbasis.h"
#include "matching/analysis_store.h"
#include "matching/functional_map.h"
#include "operators/triangle.h"
#include "spatial/surface_paths.h"

namespace genflow::detail {

namespace {

// The shapes are analysed at about this many vertices (all-pairs geodesics: 8 MB each).
constexpr Eigen::Index kVertices = 1000;

// Lengths are in units of √area, so that nothing depends on the shapes' scale. What the
// constants below were measured on: docs/measurements.md, "Intrinsic start".

// At most this many extremities per shape (the farthest on average): the clique search stays
// small on shapes with many bumps (a noisy scan).
constexpr std::size_t kMaxExtremities = 16;

// The functional map: 20 eigenfunctions, Gaussians of three widths around each landmark, and
// the commutativity weight, for unit-area shapes (eigenvalues times the area): larger weights
// made the maps worse, smaller ones no better.
constexpr Eigen::Index kFunctions = 20;
constexpr std::array<double, 3> kWidths{0.15, 0.3, 0.6};
constexpr double kCommutativity = 1e-6;
// Gaussians of the distance are blind to a reflection: on a shape with one (a human's left and
// right), the map fitted to them may follow it in places and turn the surface over there. The
// turning functions of pairs of landmarks (turning_functions()) change sign under it and join
// the Gaussians with this weight: more makes the map noisy near the landmarks.
constexpr double kTurningWeight = 0.2;

}  // namespace

IntrinsicShape analyse_intrinsic_shape(const TriangleMesh& mesh) {
    IntrinsicShape shape;
    shape.coarse = coarsen(mesh, kVertices);
    const TriangleMesh& coarse = shape.coarse.mesh;
    const double unit = std::sqrt(surface_area(coarse));
    shape.unit = unit;
    // Along the edges: chords would cut across the bends of a pose (spatial/surface_paths.h).
    const ChordGraph graph = chord_graph(coarse, 1);
    const Eigen::Index n = coarse.V.rows();
    shape.distance.resize(n, n);
#pragma omp parallel for schedule(dynamic, 16)
    for (Eigen::Index v = 0; v < n; ++v) {
        shape.distance.col(v) = path_lengths_from(graph, v) / unit;
    }
    // Between components (a scan's islands), as far as the farthest connected pair.
    const double farthest =
        (shape.distance.array() < kUnreachable).select(shape.distance, 0.0).maxCoeff();
    shape.distance = (shape.distance.array() < kUnreachable).select(shape.distance, farthest);
    shape.average = shape.distance.colwise().mean().transpose();

    for (Eigen::Index v = 0; v < n; ++v) {
        bool highest = true;
        for (Eigen::Index u = 0; u < n && highest; ++u) {
            highest = shape.distance(u, v) >= kExtremityRadius ||
                      shape.average(u) < shape.average(v) ||
                      (shape.average(u) == shape.average(v) && u >= v);
        }
        if (highest) {
            shape.extremities.push_back(v);
        }
    }
    std::sort(shape.extremities.begin(), shape.extremities.end(),
              [&](Eigen::Index a, Eigen::Index b) { return shape.average(a) > shape.average(b); });
    if (shape.extremities.size() > kMaxExtremities) {
        shape.extremities.resize(kMaxExtremities);
    }

    const LaplacianEigenbasis basis = laplacian_eigenbasis(coarse, kFunctions);
    shape.functions = unit * basis.functions;
    shape.masses = basis.masses / (unit * unit);
    shape.values = (unit * unit) * basis.values;
    return shape;
}

AnalysedShapes analysed_shapes(const std::shared_ptr<TemplateCache>& template_cache,
                               const TriangleMesh& template_level,
                               const TriangleMesh& target_level) {
    TwoAnalyses<IntrinsicShape> shapes = analysed_side_by_side<IntrinsicShape>(
        template_cache, "intrinsic shape", template_level, target_level, 0,
        [](const TriangleMesh& mesh) { return analyse_intrinsic_shape(mesh); });
    return {*shapes.of_template, std::move(shapes.of_target)};
}

Eigen::MatrixXd turning_functions(const IntrinsicShape& shape,
                                  const std::vector<Eigen::Index>& sources) {
    const TriangleMesh& mesh = shape.coarse.mesh;
    const std::size_t count = sources.size();
    Eigen::MatrixXd result =
        Eigen::MatrixXd::Zero(mesh.V.rows(), static_cast<Eigen::Index>(count * (count - 1) / 2));
    Eigen::VectorXd weight = Eigen::VectorXd::Zero(mesh.V.rows());
    std::vector<Eigen::Vector3d> gradient(count);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const Triangle triangle(mesh, f);
        if (!(triangle.double_area > 0)) {
            continue;
        }
        const Eigen::Vector3d normal = triangle.cross / triangle.double_area;
        for (std::size_t s = 0; s < count; ++s) {
            gradient[s].setZero();
            for (int k = 0; k < 3; ++k) {
                const Eigen::Vector3d opposite = triangle.x[(k + 2) % 3] - triangle.x[(k + 1) % 3];
                gradient[s] += shape.distance(mesh.F(f, k), sources[s]) * normal.cross(opposite);
            }
            gradient[s] *= shape.unit / triangle.double_area;  // as on the shape of unit area
        }
        Eigen::Index column = 0;
        for (std::size_t a = 0; a < count; ++a) {
            for (std::size_t b = a + 1; b < count; ++b) {
                const double turning = normal.dot(gradient[a].cross(gradient[b]));
                for (int k = 0; k < 3; ++k) {
                    result(mesh.F(f, k), column) += triangle.double_area * turning;
                }
                ++column;
            }
        }
        for (int k = 0; k < 3; ++k) {
            weight(mesh.F(f, k)) += triangle.double_area;
        }
    }
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
        if (weight(v) > 0) {
            result.row(v) /= weight(v);
        }
    }
    return result;
}

// The functional map C, one row at a time: the descriptors' coefficients are to correspond
// (C a ≈ b) and C to commute with the Laplacians (C Λ ≈ Λ C): (B Bᵀ + w diag((λ_j − μ_r)²)) c_r
// = B a_r, with A, B the template's and the target's coefficients and λ, μ their eigenvalues.
std::vector<Eigen::Index> landmark_map(const IntrinsicShape& from, const IntrinsicShape& to,
                                       const std::vector<Eigen::Index>& from_sources,
                                       const std::vector<Eigen::Index>& to_sources) {
    const Eigen::Index functions =
        std::min({kFunctions, from.functions.cols(), to.functions.cols()});
    const auto gaussians = static_cast<Eigen::Index>(from_sources.size() * kWidths.size());
    const Eigen::MatrixXd from_turning = turning_functions(from, from_sources);
    const Eigen::MatrixXd to_turning = turning_functions(to, to_sources);
    const Eigen::Index columns = gaussians + from_turning.cols();
    Eigen::MatrixXd from_descriptors(from.distance.rows(), columns);
    Eigen::MatrixXd to_descriptors(to.distance.rows(), columns);
    Eigen::Index column = 0;
    for (std::size_t k = 0; k < from_sources.size(); ++k) {
        for (const double width : kWidths) {
            from_descriptors.col(column) =
                (-(from.distance.col(from_sources[k]) / width).array().square()).exp();
            to_descriptors.col(column) =
                (-(to.distance.col(to_sources[k]) / width).array().square()).exp();
            ++column;
        }
    }
    from_descriptors.rightCols(from_turning.cols()) = kTurningWeight * from_turning;
    to_descriptors.rightCols(to_turning.cols()) = kTurningWeight * to_turning;
    const Eigen::MatrixXd A = from.functions.leftCols(functions).transpose() *
                              (from.masses.asDiagonal() * from_descriptors);
    const Eigen::MatrixXd B =
        to.functions.leftCols(functions).transpose() * (to.masses.asDiagonal() * to_descriptors);
    const Eigen::MatrixXd gram = B * B.transpose();
    Eigen::MatrixXd map(functions, functions);
    for (Eigen::Index r = 0; r < functions; ++r) {
        Eigen::MatrixXd system = gram;
        system.diagonal() +=
            kCommutativity * (to.values.head(functions).array() - from.values(r)).square().matrix();
        map.row(r) = system.ldlt().solve(B * A.row(r).transpose()).transpose();
    }
    return nearest_rows(from.functions.leftCols(functions) * map, to.functions.leftCols(functions));
}

}  // namespace genflow::detail
