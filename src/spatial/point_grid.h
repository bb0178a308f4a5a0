// SPDX-License-Identifier: MIT
// A uniform grid over a fixed set of 3D points for radius queries whose radius is known to be a
// few cells (the truncated pseudo-Hausdorff sums, as in the paper's Appendix A). The points are
// stored sorted by cell with a dense table of cell starts, so a query visits (2k+1)² contiguous
// runs of points, one per row of cells along x, instead of walking a tree.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

// Inlines a lambda the compiler would otherwise call: a query visits a few rows of cells, of a
// few points each, and a call per row costs as much as the points.
#if defined(__GNUC__) || defined(__clang__)
#define GENFLOW_ALWAYS_INLINE __attribute__((always_inline))
#else
#define GENFLOW_ALWAYS_INLINE
#endif

namespace genflow::detail {

/// Points found by PointGrid::collect_within(): the first `count` entries of the arrays, which
/// only grow, so that a list reused from query to query allocates nothing.
struct NeighbourList {
    std::vector<std::uint32_t> slots;
    std::vector<double> distances2;
    std::size_t count = 0;

    /// Makes room for `size` entries, keeping the first `count`.
    void reserve(std::size_t size) {
        if (size > slots.size()) {
            const std::size_t grown = std::max(size, 2 * slots.size());
            slots.resize(grown);
            distances2.resize(grown);
        }
    }
};

class PointGrid {
public:
    /// Grids the rows of `points` (#P×3, finite), each with a `weight` (#P, kept for the
    /// caller) and a positive `factor` (#P) for min_scaled_distance(), with cells of about
    /// `cell_size` (> 0); the cells are enlarged when the bounding box would need more than about
    /// 4·#P + 64 of them, so that memory stays linear.
    PointGrid(const Eigen::MatrixX3d& points, const Eigen::VectorXd& weights,
              const Eigen::VectorXd& factors, double cell_size) {
        rebuild(points, weights, factors, cell_size);
    }
    /// An empty grid, for rebuild().
    PointGrid() = default;

    /// Grids new points as the constructor does, reusing this grid's memory.
    void rebuild(const Eigen::MatrixX3d& points, const Eigen::VectorXd& weights,
                 const Eigen::VectorXd& factors, double cell_size);

    [[nodiscard]] double cell_size() const { return cell_; }
    [[nodiscard]] bool empty() const { return id_.empty(); }

    /// The number of cell rings k that a block around a query needs so that it holds every
    /// point within `distance` of the query; 0 when blocks that large would cover the whole
    /// grid anyway (k = 0 makes a query visit all points, without the block arithmetic).
    [[nodiscard]] int rings_to_cover(double distance) const {
        const double rings = std::max(1.0, std::ceil(distance / cell_));
        return rings >= static_cast<double>(std::max({dims_[0], dims_[1], dims_[2]}))
                   ? 0
                   : static_cast<int>(rings);
    }

    /// An addend of min_scaled_distance() that adds nothing: the grid's own distances.
    struct NoAddend {};

    /// min over the points p in the block of (2k+1)³ cells around the cell of `query` of
    /// factor_p·(|query − p|² + offset), with the factors given at construction; +inf for an
    /// empty block. The block holds every point within k·cell_size() of the query (which may
    /// lie outside the grid); k = 0 means all points.
    [[nodiscard]] double min_scaled_distance(const Eigen::Vector3d& query, int k,
                                             double offset) const {
        return min_scaled_distance(query, k, offset, NoAddend{});
    }

    /// min_scaled_distance() with a per-point addend: the smallest factor_p·((|query − p|² +
    /// extra(slot of p)) + offset) over the block, for distances in a space of more dimensions
    /// than the grid's (the pseudo-Hausdorff distance's descriptors). The squared distances are
    /// those collect_within() finds, to the bit.
    template <typename Extra>
    [[nodiscard]] double min_scaled_distance(const Eigen::Vector3d& query, int k, double offset,
                                             Extra&& extra) const {
        constexpr bool kPlain = std::is_same_v<std::decay_t<Extra>, NoAddend>;
        const double* x = x_.data();
        const double* y = y_.data();
        const double* z = z_.data();
        const double* factor = factor_.data();
        const auto scaled = [&](std::uint32_t p, double d2) GENFLOW_ALWAYS_INLINE {
            if constexpr (kPlain) {
                return factor[p] * (d2 + offset);
            } else {
                return factor[p] * ((d2 + extra(p)) + offset);
            }
        };
        double smallest = std::numeric_limits<double>::infinity();
        constexpr double kEverywhere = std::numeric_limits<double>::infinity();
        for_each_run(
            query, k, kEverywhere,
            [&](std::uint32_t begin, std::uint32_t end) GENFLOW_ALWAYS_INLINE {
                const double qx = query[0];
                const double qy = query[1];
                const double qz = query[2];
                // Minima local to the run stay in registers, and two of them break the
                // dependency chain of one.
                double even = std::numeric_limits<double>::infinity();
                double odd = even;
                std::uint32_t p = begin;
#if defined(__SSE2__)
                // Without an addend, two points at a time: the same per lane as the
                // scalar loop (the minimum is exact in any order, and nothing here is
                // NaN).
                if constexpr (kPlain) {
                    const PairQuery pair_query(qx, qy, qz);
                    const __m128d shift = _mm_set1_pd(offset);
                    __m128d lanes = _mm_set1_pd(even);
                    for (; p + 1 < end; p += 2) {
                        const __m128d d = pair_query.distances2(x + p, y + p, z + p);
                        lanes = _mm_min_pd(
                            lanes, _mm_mul_pd(_mm_loadu_pd(factor + p), _mm_add_pd(d, shift)));
                    }
                    even = _mm_cvtsd_f64(lanes);
                    odd = _mm_cvtsd_f64(_mm_unpackhi_pd(lanes, lanes));
                }
#endif
                for (; p + 1 < end; p += 2) {
                    even =
                        std::min(even, scaled(p, squared_distance(x[p], y[p], z[p], qx, qy, qz)));
                    odd = std::min(odd, scaled(p + 1, squared_distance(x[p + 1], y[p + 1], z[p + 1],
                                                                       qx, qy, qz)));
                }
                if (p < end) {
                    even =
                        std::min(even, scaled(p, squared_distance(x[p], y[p], z[p], qx, qy, qz)));
                }
                smallest = std::min({smallest, even, odd});
            });
        return smallest;
    }

    /// Replaces the contents of `found` by the points of the block (as above) with squared
    /// distance ≤ `radius2`, with those distances; the accessors below read a point by slot.
    void collect_within(const Eigen::Vector3d& query, int k, double radius2,
                        NeighbourList& found) const {
        found.count = 0;
        for_each_run(query, k, radius2,
                     [&](std::uint32_t begin, std::uint32_t end) GENFLOW_ALWAYS_INLINE {
                         // Locals, read once per run: the stores below could alias anything
                         // captured or reached through `this`, which would then be read again for
                         // every point.
                         const double qx = query[0];
                         const double qy = query[1];
                         const double qz = query[2];
                         const double r2 = radius2;
                         const double* x = x_.data();
                         const double* y = y_.data();
                         const double* z = z_.data();
                         found.reserve(found.count + (end - begin));
                         std::uint32_t* slots = found.slots.data();
                         double* distances2 = found.distances2.data();
                         std::size_t count = found.count;
                         // Every point is written and only the kept ones advance the count: about a
                         // third of a block is kept, in no predictable order, which a branch would
                         // mispredict.
                         std::uint32_t p = begin;
#if defined(__SSE2__)
                         // Two points at a time: the same operations in the same order per lane, so
                         // the same distances to the bit as the scalar loop below.
                         const PairQuery pair_query(qx, qy, qz);
                         const __m128d vr2 = _mm_set1_pd(r2);
                         for (; p + 1 < end; p += 2) {
                             const __m128d d = pair_query.distances2(x + p, y + p, z + p);
                             const int kept = _mm_movemask_pd(_mm_cmple_pd(d, vr2));
                             slots[count] = p;
                             _mm_storel_pd(distances2 + count, d);
                             count += static_cast<std::size_t>(kept & 1);
                             slots[count] = p + 1;
                             _mm_storeh_pd(distances2 + count, d);
                             count += static_cast<std::size_t>(kept >> 1);
                         }
#endif
                         for (; p < end; ++p) {
                             const double d = squared_distance(x[p], y[p], z[p], qx, qy, qz);
                             slots[count] = p;
                             distances2[count] = d;
                             count += d <= r2 ? 1 : 0;
                         }
                         found.count = count;
                     });
    }

    /// The total weight of the points in the block of (2k+1)³ cells around the cell of `query`
    /// (which may lie outside the grid), in O(1) from prefix sums. Every point within
    /// k·cell_size() of the query lies in that block.
    [[nodiscard]] double block_weight(const Eigen::Vector3d& query, int k) const {
        std::array<std::int64_t, 3> low{};
        std::array<std::int64_t, 3> high{};
        if (!block_cells(query, k, low, high)) {
            return 0;
        }
        for (std::int64_t& end : high) {
            ++end;  // prefix sums index one past the last cell
        }
        // Inclusion–exclusion over the corners of the box in the (dims + 1)³ prefix table.
        const auto at = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
            return prefix_weight_[static_cast<std::size_t>(
                (z * (dims_[1] + 1) + y) * (dims_[0] + 1) + x)];
        };
        return at(high[0], high[1], high[2]) - at(low[0], high[1], high[2]) -
               at(high[0], low[1], high[2]) - at(high[0], high[1], low[2]) +
               at(low[0], low[1], high[2]) + at(low[0], high[1], low[2]) +
               at(high[0], low[1], low[2]) - at(low[0], low[1], low[2]);
    }

    /// The row, in the constructor's matrix, of the point at `slot`.
    [[nodiscard]] std::uint32_t id(std::uint32_t slot) const {
        return id_[slot];
    }
    [[nodiscard]] double weight(std::uint32_t slot) const {
        return weight_[slot];
    }
    /// The `factor` of the point at `slot` (as given to the constructor).
    [[nodiscard]] double factor(std::uint32_t slot) const {
        return factor_[slot];
    }
    [[nodiscard]] Eigen::Vector3d position(std::uint32_t slot) const {
        return {x_[slot], y_[slot], z_[slot]};
    }

private:
    // |q − p|² as ((dx² + dy²) + dz²), the order of PairQuery's lanes: every loop finds the
    // same bits for the same point.
    static double squared_distance(double px, double py, double pz, double qx, double qy,
                                   double qz) {
        const double dx = px - qx;
        const double dy = py - qy;
        const double dz = pz - qz;
        return dx * dx + dy * dy + dz * dz;
    }

#if defined(__SSE2__)
    // Squared distances from a query to two consecutive points, with the scalar loops'
    // operations in their order ((dx² + dy²) + dz²) per lane: the same to the bit.
    struct PairQuery {
        __m128d x, y, z;
        PairQuery(double qx, double qy, double qz)
            : x(_mm_set1_pd(qx)), y(_mm_set1_pd(qy)), z(_mm_set1_pd(qz)) {}
        [[nodiscard]] __m128d distances2(const double* px, const double* py,
                                         const double* pz) const {
            const __m128d dx = _mm_sub_pd(_mm_loadu_pd(px), x);
            const __m128d dy = _mm_sub_pd(_mm_loadu_pd(py), y);
            const __m128d dz = _mm_sub_pd(_mm_loadu_pd(pz), z);
            return _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)),
                              _mm_mul_pd(dz, dz));
        }
    };
#endif

    void build_prefix_weights(const Eigen::VectorXd& weights);

    // ⌊v⌋ of a cell coordinate, clamped to ±1e9 (far outside any grid); std::floor is a
    // library call on baseline x86-64 and sits in the innermost setup loop.
    static std::int64_t cell_floor(double v) {
        const double clamped = std::clamp(v, -1e9, 1e9);
        const auto truncated = static_cast<std::int64_t>(clamped);
        return truncated - (clamped < static_cast<double>(truncated) ? 1 : 0);
    }

    // The cells [low, high] (inclusive, per axis) of the block of k rings around the cell of
    // `query`, clipped to the grid; false when the block misses the grid.
    bool block_cells(const Eigen::Vector3d& query, int k, std::array<std::int64_t, 3>& low,
                     std::array<std::int64_t, 3>& high) const {
        for (std::size_t a = 0; a < 3; ++a) {
            const auto axis = static_cast<Eigen::Index>(a);
            const std::int64_t cell = cell_floor((query[axis] - origin_[axis]) * inverse_cell_);
            low[a] = std::max<std::int64_t>(cell - k, 0);
            high[a] = std::min<std::int64_t>(cell + k, dims_[a] - 1);
            if (low[a] > high[a]) {
                return false;
            }
        }
        return true;
    }

    // Calls run(begin, end) for the contiguous run of sorted points of each row of cells of
    // the block around `query` (k = 0: one run of all points), leaving out the cells farther
    // than sqrt(radius2) from the query.
    template <typename Run>
    void for_each_run(const Eigen::Vector3d& query, int k, double radius2, Run&& run) const {
        if (k <= 0) {
            run(0U, static_cast<std::uint32_t>(id_.size()));
            return;
        }
        std::array<std::int64_t, 3> low{};
        std::array<std::int64_t, 3> high{};
        if (!block_cells(query, k, low, high)) {
            return;
        }
        if (radius2 == std::numeric_limits<double>::infinity()) {  // the whole block
            for (std::int64_t z = low[2]; z <= high[2]; ++z) {
                for (std::int64_t y = low[1]; y <= high[1]; ++y) {
                    const std::int64_t row = (z * dims_[1] + y) * dims_[0];
                    const std::uint32_t begin = start_[static_cast<std::size_t>(row + low[0])];
                    const std::uint32_t end = start_[static_cast<std::size_t>(row + high[0] + 1)];
                    if (begin < end) {
                        run(begin, end);
                    }
                }
            }
            return;
        }
        // The cells along `axis` that a ball of radius `half` about the query reaches.
        const auto reach = [&](std::size_t axis, double half) {
            const double q = query[static_cast<Eigen::Index>(axis)] - origin_[axis];
            return std::pair{std::max(low[axis], cell_floor((q - half) * inverse_cell_)),
                             std::min(high[axis], cell_floor((q + half) * inverse_cell_))};
        };
        // Squared distance from the query to the slab of cells `c` along `axis`.
        const auto gap2 = [&](std::size_t axis, std::int64_t c) {
            const double low_side = origin_[axis] + static_cast<double>(c) * cell_;
            const double q = query[static_cast<Eigen::Index>(axis)];
            const double gap = std::max({low_side - q, q - (low_side + cell_), 0.0});
            return gap * gap;
        };
        // Only the rows of cells the ball reaches are visited (a block has (2k+1)² rows, the
        // ball about π/4 of them), each over the ball's extent along x: clipping every row to
        // the ball's chord costs more than the few points it would skip.
        const double radius = std::sqrt(radius2);
        const auto [x_first, x_last] = reach(0, radius);
        const auto [z_first, z_last] = reach(2, radius);
        if (x_first > x_last) {
            return;
        }
        for (std::int64_t z = z_first; z <= z_last; ++z) {
            const auto [y_first, y_last] = reach(1, std::sqrt(std::max(radius2 - gap2(2, z), 0.0)));
            for (std::int64_t y = y_first; y <= y_last; ++y) {
                const std::int64_t row = (z * dims_[1] + y) * dims_[0];
                const std::uint32_t begin = start_[static_cast<std::size_t>(row + x_first)];
                const std::uint32_t end = start_[static_cast<std::size_t>(row + x_last + 1)];
                if (begin < end) {
                    run(begin, end);
                }
            }
        }
    }

    double cell_ = 1;
    double inverse_cell_ = 1;  // cells are found by multiplication, here and when sorting
    Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
    std::array<std::int64_t, 3> dims_{1, 1, 1};
    std::vector<std::uint32_t> start_;  // per cell (x fastest), plus one: first point in it
    std::vector<double> x_, y_, z_;     // coordinates in cell order
    std::vector<double> weight_;        // per point, in cell order
    std::vector<double> factor_;        // per point, in cell order
    std::vector<std::uint32_t> id_;     // original row, in cell order
    // Σ weight over the cells [0, x) × [0, y) × [0, z), on a (dims + 1)³ table (x fastest).
    std::vector<double> prefix_weight_;
    // Scratch of rebuild(), kept so that a grid rebuilt at every evaluation allocates nothing:
    // each point's cell, and the next free slot of each cell.
    std::vector<std::uint32_t> cell_of_;
    std::vector<std::uint32_t> next_slot_;
};

}  // namespace genflow::detail
