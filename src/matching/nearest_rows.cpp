// SPDX-License-Identifier: MIT
#include "matching/nearest_rows.h"

#include <algorithm>
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

// The squared distance between the boxes [low_a, high_a] and [low_b, high_b], rounded down a
// little: no pair of their points is closer. A row is the box whose corners are both the row.
template <typename LowA, typename HighA, typename LowB, typename HighB>
double box_gap2(const LowA& low_a, const HighA& high_a, const LowB& low_b, const HighB& high_b) {
    return (low_a - high_b).cwiseMax(low_b - high_a).cwiseMax(0.0).squaredNorm() * (1 - 1e-12);
}

// Whether any row a of `block` lies within reach_a + rounding of the box of `to`'s block l.
bool any_within(const Eigen::MatrixXd& block, const RowBlocks& columns, Eigen::Index l,
                const Eigen::VectorXd& reach, double rounding) {
    for (Eigen::Index i = 0; i < block.rows(); ++i) {
        if (box_gap2(block.row(i), block.row(i), columns.low.row(l), columns.high.row(l)) <=
            reach[i] + rounding) {
            return true;
        }
    }
    return false;
}

// The rows of `to` in blocks (RowBlocks), gathered block after block for the products, with
// their squared norms.
struct Candidates {
    RowBlocks blocks;
    Eigen::MatrixXd rows;        // to's rows in blocks.order
    Eigen::RowVectorXd squared;  // |b|² by to's own row index
    double rounding = 0;         // the margin of a skipped block (see nearest_rows())
};

// The nearest rows so far of one block of `from`: the smallest |b|² − 2a·b and its row of `to`
// (to.rows() while none).
struct Found {
    Eigen::VectorXd smallest;
    std::vector<Eigen::Index> row;
};

// Takes the products of `block` with the candidates' block l into `found`, column by column
// (the products are stored by columns); of equal values the first row of `to` wins, as in the
// whole product.
void take_block(const Eigen::MatrixXd& block, const Candidates& candidates, Eigen::Index l,
                Eigen::MatrixXd& products, Found& found) {
    const RowBlocks& blocks = candidates.blocks;
    products.noalias() =
        -2 * block * candidates.rows.middleRows(blocks.begin(l), blocks.size(l)).transpose();
    for (Eigen::Index c = 0; c < products.cols(); ++c) {
        const Eigen::Index j = blocks.order[static_cast<std::size_t>(blocks.begin(l) + c)];
        for (Eigen::Index i = 0; i < products.rows(); ++i) {
            const double d = products(i, c) + candidates.squared(j);
            auto& row = found.row[static_cast<std::size_t>(i)];
            if (d < found.smallest[i] || (d == found.smallest[i] && j < row)) {
                found.smallest[i] = d;
                row = j;
            }
        }
    }
}

// The nearest rows of `block` (block k of `rows`): the candidates' blocks in order of their
// boxes' distance from block k's box, each taken unless no row of the block can find a nearer
// row in it. |a − b|² = |b|² − 2a·b + |a|² is at least the boxes' distance for every pair of
// two blocks, and at least a row's distance to a box for each row in it.
Found nearest_of_block(const Eigen::MatrixXd& block, const RowBlocks& rows, Eigen::Index k,
                       const Candidates& candidates, Eigen::MatrixXd& products) {
    const RowBlocks& blocks = candidates.blocks;
    std::vector<double> lower_bound(static_cast<std::size_t>(blocks.count()));
    for (Eigen::Index l = 0; l < blocks.count(); ++l) {
        lower_bound[static_cast<std::size_t>(l)] =
            box_gap2(rows.low.row(k), rows.high.row(k), blocks.low.row(l), blocks.high.row(l));
    }
    std::vector<Eigen::Index> by_distance(lower_bound.size());
    std::iota(by_distance.begin(), by_distance.end(), Eigen::Index{0});
    std::stable_sort(by_distance.begin(), by_distance.end(), [&](Eigen::Index a, Eigen::Index b) {
        return lower_bound[static_cast<std::size_t>(a)] < lower_bound[static_cast<std::size_t>(b)];
    });
    const Eigen::VectorXd block_squared = block.rowwise().squaredNorm();
    Found found{Eigen::VectorXd::Constant(block.rows(), std::numeric_limits<double>::infinity()),
                std::vector<Eigen::Index>(static_cast<std::size_t>(block.rows()),
                                          candidates.squared.size())};
    for (const Eigen::Index l : by_distance) {
        const Eigen::VectorXd reach = found.smallest + block_squared;
        if (lower_bound[static_cast<std::size_t>(l)] > reach.maxCoeff() + candidates.rounding) {
            break;  // and every block after it
        }
        if (any_within(block, blocks, l, reach, candidates.rounding)) {
            take_block(block, candidates, l, products, found);
        }
    }
    return found;
}

}  // namespace

std::vector<Eigen::Index> nearest_rows(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to) {
    std::vector<Eigen::Index> nearest(static_cast<std::size_t>(from.rows()), 0);
    if (from.rows() == 0 || to.rows() == 0) {
        return nearest;
    }
    Candidates candidates;
    candidates.blocks = row_blocks(to, to.rows() / kColumnMultiple * kColumnMultiple, kColumnBlock,
                                   kColumnMultiple);
    candidates.rows = to(candidates.blocks.order, Eigen::all);
    candidates.squared = to.rowwise().squaredNorm().transpose();
    // The products' rounding, |b|² − 2a·b against its exact value, stays far below this (about
    // k ε (|a|² + |b|²) for k columns): a block is skipped only when even that could not bring
    // a row of it to the nearest found.
    candidates.rounding =
        1e-10 * (from.rowwise().squaredNorm().maxCoeff() + candidates.squared.maxCoeff());
    const RowBlocks rows = row_blocks(from, from.rows(), kRowBlock, 1);
    Eigen::MatrixXd block;
    Eigen::MatrixXd products;
    for (Eigen::Index k = 0; k < rows.count(); ++k) {
        const auto members = Eigen::Map<const Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1>>(
            rows.order.data() + rows.begin(k), rows.size(k));
        block = from(members, Eigen::all);
        const Found found = nearest_of_block(block, rows, k, candidates, products);
        for (Eigen::Index i = 0; i < block.rows(); ++i) {
            const Eigen::Index row = found.row[static_cast<std::size_t>(i)];
            nearest[static_cast<std::size_t>(members[i])] = row < to.rows() ? row : 0;
        }
    }
    return nearest;
}

}  // namespace genflow::detail
