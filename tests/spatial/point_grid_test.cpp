// SPDX-License-Identifier: MIT
#include "spatial/point_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "genflow/mesh/primitives.h"

namespace genflow::detail {
namespace {

// The ids found, sorted; checks the distances reported on the way. `found` is reused from
// call to call, as the energy does.
std::vector<std::uint32_t> ids_within(const PointGrid& grid, const Eigen::Vector3d& query,
                                      int rings, double radius2, NeighbourList& found) {
    grid.collect_within(query, rings, radius2, found);
    std::vector<std::uint32_t> ids;
    for (std::size_t k = 0; k < found.count; ++k) {
        const std::uint32_t slot = found.slots[k];
        EXPECT_DOUBLE_EQ(found.distances2[k], (grid.position(slot) - query).squaredNorm());
        ids.push_back(grid.id(slot));
    }
    std::sort(ids.begin(), ids.end());
    return ids;
}

// `count` values drawn uniformly from [low, high).
Eigen::VectorXd random_values(Eigen::Index count, double low, double high, unsigned seed) {
    std::mt19937 generator(seed);
    std::uniform_real_distribution<double> uniform(low, high);
    Eigen::VectorXd values(count);
    for (Eigen::Index i = 0; i < count; ++i) {
        values[i] = uniform(generator);
    }
    return values;
}

std::vector<std::uint32_t> brute_force_within(const Eigen::MatrixX3d& points,
                                              const Eigen::Vector3d& query, double radius2) {
    std::vector<std::uint32_t> ids;
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
        if ((points.row(i).transpose() - query).squaredNorm() <= radius2) {
            ids.push_back(static_cast<std::uint32_t>(i));
        }
    }
    return ids;
}

TEST(PointGrid, RadiusQueriesEqualBruteForceInsideAndOutsideTheGrid) {
    const Eigen::MatrixX3d points = make_icosphere(3).V;
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(points.rows());
    std::mt19937 generator(3);
    std::uniform_real_distribution<double> uniform(-2.5, 2.5);  // the sphere has radius 1
    NeighbourList found;
    for (const double cell : {0.05, 0.2, 1.0}) {
        const PointGrid grid(points, ones, ones, cell);
        for (int trial = 0; trial < 200; ++trial) {
            const Eigen::Vector3d query(uniform(generator), uniform(generator), uniform(generator));
            const double radius = 0.02 + 0.6 * std::abs(uniform(generator));
            const int rings = grid.rings_to_cover(radius);
            ASSERT_EQ(ids_within(grid, query, rings, radius * radius, found),
                      brute_force_within(points, query, radius * radius))
                << "cell " << cell << " trial " << trial;
        }
    }
}

TEST(PointGrid, MinScaledDistanceCoversItsBlock) {
    const Eigen::MatrixX3d points = make_icosphere(3).V;
    const Eigen::VectorXd factors = random_values(points.rows(), 0.5, 2.0, 4);
    const PointGrid grid(points, Eigen::VectorXd::Ones(points.rows()), factors, 0.1);
    for (Eigen::Index q = 0; q < points.rows(); q += 7) {
        const Eigen::Vector3d query = 1.01 * points.row(q).transpose();
        // Over all points (rings = 0) it is the exact minimum...
        double expected = std::numeric_limits<double>::infinity();
        for (Eigen::Index i = 0; i < points.rows(); ++i) {
            expected = std::min(
                expected, factors[i] * ((points.row(i).transpose() - query).squaredNorm() + 0.01));
        }
        EXPECT_DOUBLE_EQ(grid.min_scaled_distance(query, 0, 0.01), expected);
        // ...and over one ring it is never below it, and finite: the query's block holds
        // the point it was made from.
        const double one_ring = grid.min_scaled_distance(query, 1, 0.01);
        EXPECT_GE(one_ring, expected * (1 - 1e-14));
        EXPECT_LE(one_ring,
                  factors[q] * ((0.01 * points.row(q)).squaredNorm() + 0.01) * (1 + 1e-14));
    }
}

// With a per-point addend (a distance in more dimensions than the grid's), the minimum is the
// one over the points collect_within() finds in the same block, to the bit, and over all points
// it is the brute-force minimum.
TEST(PointGrid, MinScaledDistanceWithAnAddendIsTheMinimumOverTheCollectedPoints) {
    const Eigen::MatrixX3d points = make_icosphere(3).V;
    const Eigen::VectorXd factors = random_values(points.rows(), 0.5, 2.0, 6);
    const Eigen::VectorXd extra = random_values(points.rows(), 0.0, 0.3, 7);
    const PointGrid grid(points, Eigen::VectorXd::Ones(points.rows()), factors, 0.1);
    const auto extra_at = [&](std::uint32_t slot) { return extra[grid.id(slot)]; };
    NeighbourList found;
    for (Eigen::Index q = 0; q < points.rows(); q += 5) {
        const Eigen::Vector3d query = 1.02 * points.row(q).transpose();
        for (const int rings : {0, 1, 3}) {
            grid.collect_within(query, rings, std::numeric_limits<double>::infinity(), found);
            ASSERT_GT(found.count, 0U);
            double collected = std::numeric_limits<double>::infinity();
            for (std::size_t k = 0; k < found.count; ++k) {
                const std::uint32_t slot = found.slots[k];
                collected = std::min(
                    collected, grid.factor(slot) * ((found.distances2[k] + extra_at(slot)) + 0.01));
            }
            EXPECT_EQ(grid.min_scaled_distance(query, rings, 0.01, extra_at), collected)
                << "rings " << rings;
        }
        double brute_force = std::numeric_limits<double>::infinity();
        for (Eigen::Index i = 0; i < points.rows(); ++i) {
            const double d = (points.row(i).transpose() - query).squaredNorm();
            brute_force = std::min(brute_force, factors[i] * ((d + extra[i]) + 0.01));
        }
        EXPECT_NEAR(grid.min_scaled_distance(query, 0, 0.01, extra_at), brute_force,
                    1e-14 * brute_force);
    }
}

TEST(PointGrid, BlockWeightHoldsTheBallAndLiesWithinTheBlock) {
    const Eigen::MatrixX3d points = make_icosphere(3).V;
    const Eigen::VectorXd weights = random_values(points.rows(), 0.1, 2.0, 5);
    std::mt19937 generator(6);
    const auto weight_within = [&](const Eigen::Vector3d& query, double radius) {
        double sum = 0;
        for (Eigen::Index i = 0; i < points.rows(); ++i) {
            sum += (points.row(i).transpose() - query).norm() < radius ? weights[i] : 0.0;
        }
        return sum;
    };
    const double cell = 0.15;
    const PointGrid grid(points, weights, Eigen::VectorXd::Ones(points.rows()), cell);
    std::uniform_real_distribution<double> position(-1.6, 1.6);  // some queries off the grid
    for (int trial = 0; trial < 200; ++trial) {
        const Eigen::Vector3d query(position(generator), position(generator), position(generator));
        for (const int k : {0, 1, 2, 5}) {
            const double block = grid.block_weight(query, k);
            // Every point within k cells is in the block; every point of the block lies within
            // √3 (k + 1) cells.
            EXPECT_GE(block, weight_within(query, k * grid.cell_size()) - 1e-12);
            EXPECT_LE(block,
                      weight_within(query, std::sqrt(3.0) * (k + 1) * grid.cell_size()) + 1e-12);
        }
    }
    EXPECT_NEAR(grid.block_weight(Eigen::Vector3d::Zero(), 1000), weights.sum(), 1e-10);
    EXPECT_EQ(grid.block_weight(Eigen::Vector3d(10, 0, 0), 2), 0.0);
}

TEST(PointGrid, ElongatedSetsKeepTheCellTableLinear) {
    // A needle 1e6 cells long: the grid must enlarge its cells instead of allocating them all.
    Eigen::MatrixX3d points(100, 3);
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
        points.row(i) << static_cast<double>(i) * 1e4, 0.0, 0.0;
    }
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(points.rows());
    const PointGrid grid(points, ones, ones, 1.0);
    EXPECT_GT(grid.cell_size(), 1.0);
    NeighbourList found;
    EXPECT_EQ(ids_within(grid, Eigen::Vector3d(5e4, 1, 0), grid.rings_to_cover(2e4), 4e8, found),
              brute_force_within(points, Eigen::Vector3d(5e4, 1, 0), 4e8));
}

TEST(PointGrid, AnEmptySetFindsNothing) {
    const PointGrid grid(Eigen::MatrixX3d(0, 3), Eigen::VectorXd(0), Eigen::VectorXd(0), 1.0);
    EXPECT_TRUE(grid.empty());
    NeighbourList found;
    EXPECT_TRUE(ids_within(grid, Eigen::Vector3d::Zero(), 0, 1e300, found).empty());
    EXPECT_EQ(grid.min_scaled_distance(Eigen::Vector3d::Zero(), 1, 0),
              std::numeric_limits<double>::infinity());
    EXPECT_EQ(grid.block_weight(Eigen::Vector3d::Zero(), 3), 0.0);
}

}  // namespace
}  // namespace genflow::detail
