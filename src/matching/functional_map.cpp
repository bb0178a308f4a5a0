// SPDX-License-Identifier: MIT
#include "matching/functional_map.h"

#include <Eigen/SVD>
#include <algorithm>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/operators/laplacian_eigenbasis.h"
#include "spatial/point_index.h"

namespace genflow::detail {

std::vector<Eigen::Index> nearest_rows(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to) {
    // |a − b|² = |b|² − 2 a·b + |a|², the last the same for every b. Blocks of rows keep the
    // distance matrix small on meshes of ten thousand vertices.
    constexpr Eigen::Index kBlock = 1024;
    const Eigen::RowVectorXd to_squared = to.rowwise().squaredNorm().transpose();
    std::vector<Eigen::Index> nearest(static_cast<std::size_t>(from.rows()));
    for (Eigen::Index begin = 0; begin < from.rows(); begin += kBlock) {
        const Eigen::Index rows = std::min(kBlock, from.rows() - begin);
        const Eigen::MatrixXd distance =
            (-2 * from.middleRows(begin, rows) * to.transpose()).rowwise() + to_squared;
        for (Eigen::Index i = 0; i < rows; ++i) {
            distance.row(i).minCoeff(&nearest[static_cast<std::size_t>(begin + i)]);
        }
    }
    return nearest;
}

Eigen::MatrixXd fitted_functional_map(const Eigen::MatrixXd& from_functions,
                                      const Eigen::VectorXd& from_masses,
                                      const Eigen::MatrixXd& to_functions,
                                      const std::vector<Eigen::Index>& correspondence,
                                      Eigen::Index size) {
    return from_functions.leftCols(size).transpose() * from_masses.asDiagonal() *
           to_functions(correspondence, Eigen::seqN(0, size));
}

Eigen::RowVectorXd embedding_weights(const Eigen::VectorXd& values) {
    return values.array().max(1e-3 * values.maxCoeff()).rsqrt().matrix().transpose();
}

std::vector<Eigen::Index> zoom_out(const Eigen::MatrixXd& from_functions,
                                   const Eigen::VectorXd& from_masses,
                                   const Eigen::MatrixXd& to_functions,
                                   const Eigen::RowVectorXd& weights,
                                   std::vector<Eigen::Index> correspondence, Eigen::Index first,
                                   Eigen::Index count, Eigen::Index step) {
    for (Eigen::Index size = std::min(first, count);;
         size = std::min(size + std::max<Eigen::Index>(step, 1), count)) {
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(
            fitted_functional_map(from_functions, from_masses, to_functions, correspondence, size),
            Eigen::ComputeFullU | Eigen::ComputeFullV);
        const Eigen::MatrixXd orthogonal = svd.matrixU() * svd.matrixV().transpose();
        const auto scaled = weights.head(size).asDiagonal();
        correspondence = nearest_rows(from_functions.leftCols(size) * orthogonal * scaled,
                                      to_functions.leftCols(size) * scaled);
        if (size == count) {
            return correspondence;
        }
    }
}

VertexMap zoomed_out_map(const TriangleMesh& template_rest, const Eigen::MatrixX3d& deformed,
                         const TriangleMesh& target, int functions) {
    if (deformed.rows() != template_rest.V.rows()) {
        throw InvalidInput("zoomed_out_map: the deformed template has " +
                           std::to_string(deformed.rows()) + " vertices, not " +
                           std::to_string(template_rest.V.rows()));
    }
    const LaplacianEigenbasis from = laplacian_eigenbasis(template_rest, functions + 1);
    const LaplacianEigenbasis to = laplacian_eigenbasis(target, functions + 1);
    VertexMap map;
    map.template_masses = from.masses;
    // Without the constant function.
    map.functions = std::min(from.values.size(), to.values.size()) - 1;
    if (map.functions < 1) {
        return map;
    }
    const PointIndex target_points(target.V);
    std::vector<Eigen::Index> correspondence(static_cast<std::size_t>(deformed.rows()));
    for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
        correspondence[static_cast<std::size_t>(i)] =
            target_points.nearest(deformed.row(i).transpose()).first;
    }
    const auto count = map.functions;
    constexpr Eigen::Index kFirstSize = 10;
    constexpr Eigen::Index kStep = 5;
    map.target_vertex =
        zoom_out(from.functions.middleCols(1, count), from.masses,
                 to.functions.middleCols(1, count), embedding_weights(to.values.segment(1, count)),
                 std::move(correspondence), kFirstSize, count, kStep);
    return map;
}

}  // namespace genflow::detail
