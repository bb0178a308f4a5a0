// SPDX-License-Identifier: MIT
#include "matching/nearest_rows.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace genflow::detail {

namespace {

// At most this many rows of `from`, and of `to`, a block: boxes small enough to be passed by, and
// products large enough for the kernel's speed. On ZoomOut's embeddings of two 5K FAUST
// meshes (10 to 60 functions), 64 and 128 took 0.34 times the whole product's time; 64 and
// 256, 0.36 times (0.43 without the test of each row against a box); 32 and 64, 0.35; 16 and
// 64, 0.41.
constexpr Eigen::Index kRowBlock = 64;
constexpr Eigen::Index kColumnBlock = 128;
// Each block of `to` holds a multiple of this many rows, its last to.rows() mod 8 rows (in their
// order) excepted, which make a block of their own: the product kernel computes a column in its
// main path in the first and in its remainder path in the second, as it does in the whole
// product (8: a multiple of its column count on every SIMD width), and so to the same bits.
constexpr Eigen::Index kColumnMultiple = 8;

// The rows of a matrix in blocks of rows near one another, each with its bounding box.
struct RowBlocks {
    std::vector<Eigen::Index> order;    // the rows, block after block
    std::vector<Eigen::Index> ends{0};  // block k: order[ends[k]] … order[ends[k + 1] − 1]
    Eigen::MatrixXd low;                // per block: the smallest of each coordinate
    Eigen::MatrixXd high;               // … and the largest

    [[nodiscard]] Eigen::Index count() const { return static_cast<Eigen::Index>(ends.size()) - 1; }
    [[nodiscard]] Eigen::Index begin(Eigen::Index k) const {
        return ends[static_cast<std::size_t>(k)];
    }
    [[nodiscard]] Eigen::Index size(Eigen::Index k) const {
        return ends[static_cast<std::size_t>(k) + 1] - ends[static_cast<std::size_t>(k)];
    }
};

// Cuts order[begin, end) in halves at the median of its widest coordinate, each a multiple of
// `multiple` rows, until at most `largest` rows remain in each (a k-d tree's leaves).
void split(const Eigen::MatrixXd& points, Eigen::Index begin, Eigen::Index end,
           Eigen::Index largest, Eigen::Index multiple, RowBlocks& blocks) {
    const auto first = blocks.order.begin() + begin;
    const auto last = blocks.order.begin() + end;
    if (end - begin <= largest) {
        blocks.ends.push_back(end);
        return;
    }
    Eigen::Index widest = 0;
    double widest_extent = -1;
    for (Eigen::Index c = 0; c < points.cols(); ++c) {
        const auto [low, high] = std::minmax_element(
            first, last,
            [&](Eigen::Index a, Eigen::Index b) { return points(a, c) < points(b, c); });
        const double extent = points(*high, c) - points(*low, c);
        if (extent > widest_extent) {
            widest = c;
            widest_extent = extent;
        }
    }
    const Eigen::Index half = std::max(multiple, (end - begin) / 2 / multiple * multiple);
    std::nth_element(first, first + half, last, [&](Eigen::Index a, Eigen::Index b) {
        return points(a, widest) < points(b, widest);
    });
    split(points, begin, begin + half, largest, multiple, blocks);
    split(points, begin + half, end, largest, multiple, blocks);
}

// The blocks of the first `tree_rows` rows of `points` (a multiple of `multiple`), then, if any
// rows remain, one block of them in their order.
RowBlocks row_blocks(const Eigen::MatrixXd& points, Eigen::Index tree_rows, Eigen::Index largest,
                     Eigen::Index multiple) {
    RowBlocks blocks;
    blocks.order.resize(static_cast<std::size_t>(points.rows()));
    std::iota(blocks.order.begin(), blocks.order.end(), Eigen::Index{0});
    if (tree_rows > 0) {
        split(points, 0, tree_rows, largest, multiple, blocks);
    }
    if (points.rows() > tree_rows) {
        blocks.ends.push_back(points.rows());
    }
    blocks.low.resize(blocks.count(), points.cols());
    blocks.high.resize(blocks.count(), points.cols());
    for (Eigen::Index k = 0; k < blocks.count(); ++k) {
        blocks.low.row(k).setConstant(std::numeric_limits<double>::infinity());
        blocks.high.row(k).setConstant(-std::numeric_limits<double>::infinity());
        for (Eigen::Index t = blocks.begin(k); t < blocks.begin(k) + blocks.size(k); ++t) {
            const auto row = points.row(blocks.order[static_cast<std::size_t>(t)]);
            blocks.low.row(k) = blocks.low.row(k).cwiseMin(row);
            blocks.high.row(k) = blocks.high.row(k).cwiseMax(row);
        }
    }
    return blocks;
}

// The squared distance between two boxes, rounded down a little: no pair of their points is
// closer.
double box_distance2(const RowBlocks& a, Eigen::Index k, const RowBlocks& b, Eigen::Index l) {
    const Eigen::RowVectorXd gap =
        (a.low.row(k) - b.high.row(l)).cwiseMax(b.low.row(l) - a.high.row(k)).cwiseMax(0.0);
    return gap.squaredNorm() * (1 - 1e-12);
}

// Whether any row a of `block` lies within reach_a + rounding of the box of `to`'s block l (the
// squared distance to the box rounded down a little).
bool any_within(const Eigen::MatrixXd& block, const RowBlocks& columns, Eigen::Index l,
                const Eigen::VectorXd& reach, double rounding) {
    for (Eigen::Index i = 0; i < block.rows(); ++i) {
        const double distance2 = (columns.low.row(l) - block.row(i))
                                     .cwiseMax(block.row(i) - columns.high.row(l))
                                     .cwiseMax(0.0)
                                     .squaredNorm();
        if (distance2 * (1 - 1e-12) <= reach[i] + rounding) {
            return true;
        }
    }
    return false;
}

}  // namespace

std::vector<Eigen::Index> nearest_rows(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to) {
    std::vector<Eigen::Index> nearest(static_cast<std::size_t>(from.rows()), 0);
    if (from.rows() == 0 || to.rows() == 0) {
        return nearest;
    }
    const Eigen::RowVectorXd to_squared = to.rowwise().squaredNorm().transpose();
    const RowBlocks columns = row_blocks(to, to.rows() / kColumnMultiple * kColumnMultiple,
                                         kColumnBlock, kColumnMultiple);
    const RowBlocks rows = row_blocks(from, from.rows(), kRowBlock, 1);
    const Eigen::MatrixXd to_in_blocks = to(columns.order, Eigen::all);
    // The products' rounding, |b|² − 2a·b against its exact value, stays far below this (about
    // k ε (|a|² + |b|²) for k columns); a block is skipped only when even that cannot bring it
    // to a row already found.
    const double rounding =
        1e-10 * (from.rowwise().squaredNorm().maxCoeff() + to_squared.maxCoeff());
    std::vector<Eigen::Index> by_distance(static_cast<std::size_t>(columns.count()));
    std::vector<double> lower_bound(by_distance.size());
    Eigen::MatrixXd block;
    Eigen::MatrixXd products;
    for (Eigen::Index k = 0; k < rows.count(); ++k) {
        block.resize(rows.size(k), from.cols());
        for (Eigen::Index i = 0; i < block.rows(); ++i) {
            block.row(i) = from.row(rows.order[static_cast<std::size_t>(rows.begin(k) + i)]);
        }
        const Eigen::VectorXd block_squared = block.rowwise().squaredNorm();
        for (Eigen::Index l = 0; l < columns.count(); ++l) {
            lower_bound[static_cast<std::size_t>(l)] = box_distance2(rows, k, columns, l);
        }
        std::iota(by_distance.begin(), by_distance.end(), Eigen::Index{0});
        std::stable_sort(by_distance.begin(), by_distance.end(),
                         [&](Eigen::Index a, Eigen::Index b) {
                             return lower_bound[static_cast<std::size_t>(a)] <
                                    lower_bound[static_cast<std::size_t>(b)];
                         });
        Eigen::VectorXd smallest =
            Eigen::VectorXd::Constant(block.rows(), std::numeric_limits<double>::infinity());
        std::vector<Eigen::Index> chosen(static_cast<std::size_t>(block.rows()), to.rows());
        for (const Eigen::Index l : by_distance) {
            // |a − b|² = |b|² − 2a·b + |a|² is at least the boxes' distance for every pair of the
            // blocks, and at least a row's distance to the box of `to`'s for each of its rows.
            const Eigen::VectorXd reach = smallest + block_squared;
            if (lower_bound[static_cast<std::size_t>(l)] > reach.maxCoeff() + rounding) {
                break;  // and every block after it
            }
            if (!any_within(block, columns, l, reach, rounding)) {
                continue;
            }
            products.noalias() =
                -2 * block * to_in_blocks.middleRows(columns.begin(l), columns.size(l)).transpose();
            // The minima of all rows at once, column by column (the products are stored by
            // columns); of equal ones, the first row of `to` wins, as in the whole product.
            for (Eigen::Index c = 0; c < products.cols(); ++c) {
                const Eigen::Index j =
                    columns.order[static_cast<std::size_t>(columns.begin(l) + c)];
                for (Eigen::Index i = 0; i < products.rows(); ++i) {
                    const double d = products(i, c) + to_squared(j);
                    if (d < smallest[i] ||
                        (d == smallest[i] && j < chosen[static_cast<std::size_t>(i)])) {
                        smallest[i] = d;
                        chosen[static_cast<std::size_t>(i)] = j;
                    }
                }
            }
        }
        for (Eigen::Index i = 0; i < block.rows(); ++i) {
            const Eigen::Index row = rows.order[static_cast<std::size_t>(rows.begin(k) + i)];
            const Eigen::Index found = chosen[static_cast<std::size_t>(i)];
            nearest[static_cast<std::size_t>(row)] = found < to.rows() ? found : 0;
        }
    }
    return nearest;
}

}  // namespace genflow::detail
