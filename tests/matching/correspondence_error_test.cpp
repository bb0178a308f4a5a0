// SPDX-License-Identifier: MIT
#include "genflow/matching/correspondence_error.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <numeric>
#include <queue>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"

namespace genflow {
namespace {

constexpr double kSheet = 1.0;    // length of each sheet
constexpr double kRadius = 0.05;  // of the fold: the sheets are 2·kRadius apart
constexpr double kWidth = 0.3;

// A strip folded into a U: the bottom sheet z = 0 for x in [0, 1], a half-cylinder about
// x = 1, the top sheet z = 0.1 back to x = 0. Points straight above one another are 0.1 apart
// in space and up to 2.16 apart along the surface: a stand-in for two fingers side by side.
// With a smaller `radius`, the sheets nearly touch.
TriangleMesh folded_strip(double radius = kRadius) {
    TriangleMesh strip = make_grid(60, 1.0);
    const double length = 2 * kSheet + std::numbers::pi * radius;
    for (Eigen::Index i = 0; i < strip.V.rows(); ++i) {
        const double u = strip.V(i, 0) * length;
        const double y = strip.V(i, 1) * kWidth;
        if (u <= kSheet) {
            strip.V.row(i) << u, y, 0;
        } else if (u <= kSheet + std::numbers::pi * radius) {
            const double angle = (u - kSheet) / radius;
            strip.V.row(i) << kSheet + radius * std::sin(angle), y, radius * (1 - std::cos(angle));
        } else {
            strip.V.row(i) << kSheet - (u - kSheet - std::numbers::pi * radius), y, 2 * radius;
        }
    }
    return strip;
}

bool on_top_sheet(const Eigen::RowVector3d& x) {
    return x.z() > 2 * kRadius - 1e-12;
}

TEST(CorrespondenceError, TheGroundTruthItselfHasNoError) {
    const TriangleMesh truth = folded_strip();
    const CorrespondenceError error = correspondence_error(truth.V, truth);
    EXPECT_EQ(error.distance.size(), truth.V.rows());
    EXPECT_EQ(error.max, 0);
    EXPECT_EQ(error.stranded_count, 0);
    EXPECT_EQ(error.reversed.size(), static_cast<std::size_t>(truth.F.rows()));
    EXPECT_EQ(error.reversed_count, 0);

    // Moved as a whole by t: every vertex is |t| off, so mean, median and max are |t| over the
    // diagonal; none lands farther along the surface than straight.
    const Eigen::RowVector3d t(0.01, -0.02, 0.005);
    const CorrespondenceError moved = correspondence_error(truth.V.rowwise() + t, truth);
    const double expected = t.norm() / bounding_box_diagonal(truth);
    EXPECT_NEAR(moved.mean, expected, 1e-15);
    EXPECT_NEAR(moved.median, expected, 1e-15);
    EXPECT_NEAR(moved.max, expected, 1e-15);
    EXPECT_EQ(moved.stranded_count, 0);
}

TEST(CorrespondenceError, PointsPutOnTheOtherSheetAreStranded) {
    const TriangleMesh truth = folded_strip();
    const double diagonal = bounding_box_diagonal(truth);
    Eigen::MatrixX3d deformed = truth.V;
    Eigen::Index moved = 0;
    for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
        // Far enough from the fold that the way round (2 (1 − x) + π r) is more than twice the
        // gap 2r.
        if (on_top_sheet(truth.V.row(i)) && truth.V(i, 0) < 0.8) {
            deformed(i, 2) = 0;
            ++moved;
        }
    }
    ASSERT_GT(moved, 1000);
    const CorrespondenceError error = correspondence_error(deformed, truth);
    EXPECT_EQ(error.stranded_count, moved);
    for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
        EXPECT_EQ(error.stranded[static_cast<std::size_t>(i)], deformed(i, 2) != truth.V(i, 2));
    }
    EXPECT_NEAR(error.max, 2 * kRadius / diagonal, 1e-12);
    EXPECT_NEAR(
        error.mean,
        static_cast<double>(moved) / static_cast<double>(truth.V.rows()) * 2 * kRadius / diagonal,
        1e-12);

    // A detour allowance longer than any way round strands nothing.
    EXPECT_EQ(correspondence_error(deformed, truth, {.detour = 30}).stranded_count, 0);
}

// Where the ground truth's sheets nearly touch (0.01 apart, under half the mean edge length),
// vertices of the top sheet put 0.006 below their place lie nearer the bottom sheet, far along
// the surface: within an edge length of where they belong, they are at their place.
TEST(CorrespondenceError, VerticesAtTheirPlaceWhereSurfacesTouchAreNotStranded) {
    constexpr double kTouching = 0.005;
    const TriangleMesh truth = folded_strip(kTouching);
    ASSERT_GT(mean_edge_length(truth), 2 * (2 * kTouching));
    Eigen::MatrixX3d deformed = truth.V;
    Eigen::Index moved = 0;
    for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
        if (truth.V(i, 2) > 2 * kTouching - 1e-12 && truth.V(i, 0) < 0.8) {
            deformed(i, 2) -= 0.006;
            ++moved;
        }
    }
    ASSERT_GT(moved, 1000);
    EXPECT_EQ(correspondence_error(deformed, truth).stranded_count, 0);
    // Without the tolerance, the nearest surface decides: each is stranded on the other sheet.
    EXPECT_EQ(correspondence_error(deformed, truth, {.placement_tolerance = 0}).stranded_count,
              moved);
    // Put well off their place (0.3 along x, about ten edges) and onto the top sheet: the
    // tolerance keeps none of them.
    deformed = truth.V;
    Eigen::Index lifted = 0;
    for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
        if (truth.V(i, 2) == 0 && truth.V(i, 0) < 0.5) {
            deformed(i, 0) += 0.3;
            deformed(i, 2) = 2 * kTouching + 0.001;  // just above the top sheet
            ++lifted;
        }
    }
    ASSERT_GT(lifted, 500);
    EXPECT_EQ(correspondence_error(deformed, truth).stranded_count, lifted);
}

TEST(CorrespondenceError, PointsSlidAlongTheirOwnSheetAreOffButNotStranded) {
    const TriangleMesh truth = folded_strip();
    const double diagonal = bounding_box_diagonal(truth);
    Eigen::MatrixX3d deformed = truth.V;
    for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
        if (truth.V(i, 2) == 0 && truth.V(i, 0) <= 0.5) {
            deformed(i, 0) += 0.4;  // over 3 times the strand length (10 % of the diagonal)
        }
    }
    const CorrespondenceError error = correspondence_error(deformed, truth);
    EXPECT_NEAR(error.max, 0.4 / diagonal, 1e-12);
    EXPECT_EQ(error.stranded_count, 0);
    // No path is shorter than the straight line: a detour allowance below 1 is refused.
    EXPECT_THROW((void)correspondence_error(deformed, truth, {.detour = 0.5}), InvalidInput);
}

TEST(CorrespondenceError, ATurnedSphereSlidesAlongItselfAndStrandsNothing) {
    const TriangleMesh truth = make_icosphere(4);
    for (const double degrees : {5.0, 20.0, 60.0}) {
        const Eigen::Matrix3d turn = Eigen::AngleAxisd(degrees * std::numbers::pi / 180,
                                                       Eigen::Vector3d(0.3, 0.2, 1).normalized())
                                         .toRotationMatrix();
        const Eigen::MatrixX3d deformed = truth.V * turn.transpose();
        const CorrespondenceError error = correspondence_error(deformed, truth);
        EXPECT_EQ(error.stranded_count, 0) << degrees;
        EXPECT_EQ(error.reversed_count, 0) << degrees;  // a turn keeps every face's side
    }
}

// A "hand" put back to front in its own place: the half x ≥ 1/2 of a square sheet turned 180°
// about its midline y = 1/2. Every point stays on the sheet, no farther from where it belongs
// along it than straight, so nothing is stranded; but that half's faces face the other way.
TEST(CorrespondenceError, APartPutBackToFrontHasItsFacesReversed) {
    constexpr int kCells = 60;
    const TriangleMesh truth = make_grid(kCells, 1.0);
    Eigen::MatrixX3d deformed = truth.V;
    for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
        if (truth.V(i, 0) > 0.5 - 1e-12) {
            deformed(i, 1) = 1 - truth.V(i, 1);
            deformed(i, 2) = -truth.V(i, 2);
        }
    }
    const CorrespondenceError error = correspondence_error(deformed, truth);
    EXPECT_EQ(error.stranded_count, 0);
    EXPECT_GT(error.max, 0.5);  // the half's corners swapped: |Δy| = 1 over a diagonal √2
    // Every face of that half, and of the column of cells along x = 1/2 at most.
    EXPECT_GE(error.reversed_area, 0.5 - 1e-12);
    EXPECT_LE(error.reversed_area, 0.5 + 1.0 / kCells + 1e-12);
    for (Eigen::Index f = 0; f < truth.F.rows(); ++f) {
        const double left = truth.V(truth.F.row(f), Eigen::all).col(0).minCoeff();
        if (left > 0.5 - 1e-12) {
            EXPECT_TRUE(error.reversed[static_cast<std::size_t>(f)]) << f;
        }
        const double right = truth.V(truth.F.row(f), Eigen::all).col(0).maxCoeff();
        if (right < 0.5 - 1e-12) {
            EXPECT_FALSE(error.reversed[static_cast<std::size_t>(f)]) << f;
        }
    }

    // The whole sheet mirrored in its own plane (x → 1 − x): on itself, every face turned over.
    Eigen::MatrixX3d mirrored = truth.V;
    mirrored.col(0) = 1 - truth.V.col(0).array();
    const CorrespondenceError all = correspondence_error(mirrored, truth);
    EXPECT_EQ(all.stranded_count, 0);
    EXPECT_EQ(all.reversed_count, truth.F.rows());
    EXPECT_NEAR(all.reversed_area, 1, 1e-12);
}

// The chords between vertices at most two edges apart, which correspondence_error() walks.
std::vector<std::set<Eigen::Index>> chords(const TriangleMesh& mesh) {
    const auto n = static_cast<std::size_t>(mesh.V.rows());
    std::vector<std::set<Eigen::Index>> ring(n);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            ring[static_cast<std::size_t>(mesh.F(f, k))].insert(mesh.F(f, (k + 1) % 3));
            ring[static_cast<std::size_t>(mesh.F(f, (k + 1) % 3))].insert(mesh.F(f, k));
        }
    }
    std::vector<std::set<Eigen::Index>> reach(n);
    for (std::size_t v = 0; v < n; ++v) {
        for (const Eigen::Index w : ring[v]) {
            reach[v].insert(w);
            reach[v].insert(ring[static_cast<std::size_t>(w)].begin(),
                            ring[static_cast<std::size_t>(w)].end());
        }
        reach[v].erase(static_cast<Eigen::Index>(v));
    }
    return reach;
}

// The path lengths from `source` over those chords, by a full Dijkstra.
std::vector<double> chord_distances(const TriangleMesh& mesh,
                                    const std::vector<std::set<Eigen::Index>>& reach,
                                    Eigen::Index source) {
    std::vector<double> distance(reach.size(), std::numeric_limits<double>::infinity());
    using Entry = std::pair<double, Eigen::Index>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    distance[static_cast<std::size_t>(source)] = 0;
    queue.emplace(0.0, source);
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > distance[static_cast<std::size_t>(v)]) {
            continue;
        }
        for (const Eigen::Index w : reach[static_cast<std::size_t>(v)]) {
            const double through = d + (mesh.V.row(v) - mesh.V.row(w)).norm();
            if (through < distance[static_cast<std::size_t>(w)]) {
                distance[static_cast<std::size_t>(w)] = through;
                queue.emplace(through, w);
            }
        }
    }
    return distance;
}

// Every vertex put where another one is, at random: the landmarks' bounds and the search they
// steer decide each one as a full search does (stranded when the path is longer than both the
// strand length and twice the straight distance).
TEST(CorrespondenceError, VerticesPutOnOthersAreJudgedAsByAFullSearch) {
    const TriangleMesh truth = folded_strip();
    const double diagonal = bounding_box_diagonal(truth);
    std::vector<Eigen::Index> other(static_cast<std::size_t>(truth.V.rows()));
    std::iota(other.begin(), other.end(), Eigen::Index{0});
    std::shuffle(other.begin(), other.end(), std::mt19937(5));
    const Eigen::MatrixX3d deformed = truth.V(other, Eigen::all);
    const CorrespondenceError error = correspondence_error(deformed, truth);
    const std::vector<std::set<Eigen::Index>> reach = chords(truth);
    int stranded = 0;
    int kept = 0;
    for (Eigen::Index i = 0; i < truth.V.rows(); i += 13) {
        const Eigen::Index j = other[static_cast<std::size_t>(i)];
        const double straight = (truth.V.row(j) - truth.V.row(i)).norm();
        const double path = chord_distances(truth, reach, i)[static_cast<std::size_t>(j)];
        const bool expected = path > std::max(0.1 * diagonal, 2 * straight);
        EXPECT_EQ(error.stranded[static_cast<std::size_t>(i)], expected) << i;
        (expected ? stranded : kept) += 1;
    }
    // Both outcomes are exercised: across the fold, and along a sheet.
    EXPECT_GT(stranded, 40);
    EXPECT_GT(kept, 40);
}

// No path joins two separate shapes: a vertex put on the other one is stranded however near.
TEST(CorrespondenceError, AVertexPutOnAnotherComponentIsStranded) {
    const TriangleMesh sphere = make_icosphere(3);
    const Eigen::Index n = sphere.V.rows();
    TriangleMesh truth;
    truth.V.resize(2 * n, 3);
    truth.V << sphere.V, sphere.V.rowwise() + Eigen::RowVector3d(2.1, 0, 0);
    truth.F.resize(2 * sphere.F.rows(), 3);
    truth.F << sphere.F, sphere.F.array() + static_cast<int>(n);
    Eigen::MatrixX3d deformed = truth.V;
    int moved = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
        if (sphere.V(i, 0) > 0.9) {  // the cap of the first sphere facing the second, 0.1 away
            deformed.row(i) = truth.V.row(i) + Eigen::RowVector3d(0.2, 0, 0);
            ++moved;
        }
    }
    ASSERT_GT(moved, 10);
    const CorrespondenceError error = correspondence_error(deformed, truth);
    EXPECT_EQ(error.stranded_count, moved);
    for (Eigen::Index i = 0; i < n; ++i) {
        EXPECT_EQ(error.stranded[static_cast<std::size_t>(i)], sphere.V(i, 0) > 0.9) << i;
    }
}

TEST(CorrespondenceError, RefusesMismatchedOrNonFiniteInput) {
    const TriangleMesh truth = folded_strip();
    EXPECT_THROW((void)correspondence_error(truth.V.topRows(10), truth), InvalidInput);
    Eigen::MatrixX3d deformed = truth.V;
    deformed(3, 1) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW((void)correspondence_error(deformed, truth), InvalidInput);
    EXPECT_THROW((void)correspondence_error(truth.V, truth, {.length = 0}), InvalidInput);
    EXPECT_THROW((void)correspondence_error(truth.V, truth, {.placement_tolerance = -1}),
                 InvalidInput);
    TriangleMesh faceless = truth;
    faceless.F.resize(0, 3);
    EXPECT_THROW((void)correspondence_error(truth.V, faceless), InvalidInput);
}

}  // namespace
}  // namespace genflow
