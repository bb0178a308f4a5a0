// SPDX-License-Identifier: MIT
// nearest_rows() skips the blocks of rows that cannot hold a nearest one: it must find the rows
// the whole matrix product finds, to the index, in the embeddings ZoomOut matches in.
#include "matching/nearest_rows.h"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <array>
#include <limits>
#include <vector>

#include "genflow/operators/laplacian_eigenbasis.h"
#include "matching/functional_map.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// The first of the smallest |b|² − 2a·b per row, from the whole product −2·from·toᵀ.
std::vector<Eigen::Index> whole_product_nearest_rows(const Eigen::MatrixXd& from,
                                                     const Eigen::MatrixXd& to) {
    const Eigen::MatrixXd products = -2 * from * to.transpose();
    const Eigen::RowVectorXd to_squared = to.rowwise().squaredNorm().transpose();
    std::vector<Eigen::Index> nearest(static_cast<std::size_t>(from.rows()), 0);
    for (Eigen::Index i = 0; i < from.rows(); ++i) {
        double smallest = std::numeric_limits<double>::infinity();
        for (Eigen::Index j = 0; j < to.rows(); ++j) {
            const double d = products(i, j) + to_squared(j);
            if (d < smallest) {
                smallest = d;
                nearest[static_cast<std::size_t>(i)] = j;
            }
        }
    }
    return nearest;
}

// ZoomOut's embeddings of two noisy spheres at several sizes (the template's functions through an
// orthogonal map, both weighted by 1/√λ), and of parts of them whose row counts are not
// multiples of the blocks'.
TEST(NearestRows, FindsTheRowsOfTheWholeProductInSpectralEmbeddings) {
    const LaplacianEigenbasis from_basis =
        laplacian_eigenbasis(test::noisy_icosphere(3, 0.1, 1), 41);
    const LaplacianEigenbasis to_basis = laplacian_eigenbasis(test::noisy_icosphere(3, 0.1, 2), 41);
    for (const Eigen::Index size : {10, 25, 40}) {
        const Eigen::RowVectorXd weights =
            detail::embedding_weights(to_basis.values.segment(1, size));
        const Eigen::MatrixXd turn =
            Eigen::HouseholderQR<Eigen::MatrixXd>(test::random_matrix(size, size, 3))
                .householderQ();
        const Eigen::MatrixXd from =
            from_basis.functions.middleCols(1, size) * turn * weights.asDiagonal();
        const Eigen::MatrixXd to = to_basis.functions.middleCols(1, size) * weights.asDiagonal();
        EXPECT_EQ(detail::nearest_rows(from, to), whole_product_nearest_rows(from, to)) << size;
        const Eigen::MatrixXd some_from = from.topRows(401);
        const Eigen::MatrixXd some_to = to.topRows(637);  // 637 = 8 · 79 + 5
        EXPECT_EQ(detail::nearest_rows(some_from, some_to),
                  whole_product_nearest_rows(some_from, some_to))
            << size;
    }
}

// Points in general position, far and near, and the smallest cases.
TEST(NearestRows, FindsTheRowsOfTheWholeProductInRandomPoints) {
    for (const auto& [rows, columns, dims] :
         {std::array<Eigen::Index, 3>{1500, 1203, 6}, {700, 9, 3}, {5, 7, 3}, {300, 2000, 60}}) {
        const Eigen::MatrixXd from = test::random_matrix(rows, dims, 4);
        const Eigen::MatrixXd to = 1.3 * test::random_matrix(columns, dims, 5);
        EXPECT_EQ(detail::nearest_rows(from, to), whole_product_nearest_rows(from, to))
            << rows << " × " << columns;
    }
    EXPECT_EQ(detail::nearest_rows(Eigen::MatrixXd(4, 3), Eigen::MatrixXd(0, 3)),
              std::vector<Eigen::Index>(4, 0));
    EXPECT_TRUE(detail::nearest_rows(Eigen::MatrixXd(0, 3), Eigen::MatrixXd(4, 3)).empty());
}

}  // namespace
}  // namespace genflow
