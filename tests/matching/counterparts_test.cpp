// SPDX-License-Identifier: MIT
// Counterparts (counterparts.h): among the target's points near where the match put a vertex,
// the one the eigenfunctions agree with.
#include "matching/counterparts.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/matching/correspondence.h"
#include "genflow/operators/laplacian_eigenbasis.h"
#include "matching/functional_map.h"

namespace genflow::detail {
namespace {

// A closed tube of radius 0.5 bent into a hairpin: two straight legs along +x, 6 and 4 long
// (unequal, so that no symmetry swaps them), side by side with `gap` between their surfaces,
// joined by a half turn at x = 0 and closed by a fan at each end. The legs touch nearly in
// space and are far apart along the surface, as a finger and the next one are.
TriangleMesh hairpin(double gap) {
    constexpr double kRadius = 0.5;
    constexpr int kSides = 16;
    constexpr double kSpacing = 0.2;          // between rings along the centre line
    const double offset = kRadius + gap / 2;  // the legs' centre lines at y = ±offset
    std::vector<Eigen::Vector3d> centres;
    std::vector<Eigen::Vector3d> normals;  // in the plane z = 0, across the centre line
    for (double x = 6; x > 0; x -= kSpacing) {
        centres.emplace_back(x, offset, 0);
        normals.emplace_back(0, 1, 0);
    }
    const int turn_rings = static_cast<int>(std::ceil(std::numbers::pi * offset / kSpacing));
    for (int k = 0; k <= turn_rings; ++k) {
        const double angle = std::numbers::pi / 2 + std::numbers::pi * k / turn_rings;
        const Eigen::Vector3d outward(std::cos(angle), std::sin(angle), 0);
        centres.push_back(offset * outward);
        normals.push_back(outward);
    }
    for (double x = kSpacing; x <= 4; x += kSpacing) {
        centres.emplace_back(x, -offset, 0);
        normals.emplace_back(0, -1, 0);
    }
    const auto rings = static_cast<int>(centres.size());
    TriangleMesh mesh;
    mesh.V.resize(rings * kSides + 2, 3);
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < kSides; ++s) {
            const double angle = 2 * std::numbers::pi * s / kSides;
            mesh.V.row(r * kSides + s) =
                (centres[static_cast<std::size_t>(r)] +
                 kRadius * (std::cos(angle) * normals[static_cast<std::size_t>(r)] +
                            std::sin(angle) * Eigen::Vector3d::UnitZ()))
                    .transpose();
        }
    }
    const int first_cap = rings * kSides;
    mesh.V.row(first_cap) = centres.front().transpose() + Eigen::RowVector3d(0.3, 0, 0);
    mesh.V.row(first_cap + 1) = centres.back().transpose() + Eigen::RowVector3d(0.3, 0, 0);
    std::vector<Eigen::Vector3i> faces;
    for (int r = 0; r + 1 < rings; ++r) {
        for (int s = 0; s < kSides; ++s) {
            const int a = r * kSides + s;
            const int b = r * kSides + (s + 1) % kSides;
            faces.emplace_back(a, b, a + kSides);
            faces.emplace_back(b, b + kSides, a + kSides);
        }
    }
    for (int s = 0; s < kSides; ++s) {
        faces.emplace_back(first_cap, (s + 1) % kSides, s);
        const int last = (rings - 1) * kSides;
        faces.emplace_back(first_cap + 1, last + s, last + (s + 1) % kSides);
    }
    mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t f = 0; f < faces.size(); ++f) {
        mesh.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
    }
    return mesh;
}

constexpr Eigen::Index kFunctions = 41;

struct Hairpin {
    static constexpr double kGap = 0.05;
    TriangleMesh mesh = hairpin(kGap);
    LaplacianEigenbasis basis = laplacian_eigenbasis(mesh, kFunctions);
    /// The second leg's vertices nearest to the first leg, beyond the turn.
    [[nodiscard]] std::vector<Eigen::Index> facing_vertices() const {
        std::vector<Eigen::Index> facing;
        for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
            if (mesh.V(v, 0) > 1.5 && mesh.V(v, 1) < 0 && mesh.V(v, 1) > -0.6 * kGap) {
                facing.push_back(v);
            }
        }
        return facing;
    }
};

TEST(Counterparts, AreTheVerticesThemselvesWhereTheMatchIsExact) {
    const Hairpin pin;
    const Counterparts found =
        intrinsic_counterparts(pin.basis, pin.basis, pin.mesh, pin.mesh.V, {});
    EXPECT_EQ(found.moved, 0);
    EXPECT_EQ(found.points, pin.mesh.V);
}

// Vertices put nearer to the other leg than to their own: the closest points are on the wrong
// leg, and the eigenfunctions bring each back to its own vertex.
TEST(Counterparts, TakeAVertexBackFromAPartItTouches) {
    const Hairpin pin;
    const std::vector<Eigen::Index> facing = pin.facing_vertices();
    ASSERT_GE(facing.size(), 10U);
    Eigen::MatrixX3d deformed = pin.mesh.V;
    for (const Eigen::Index v : facing) {
        deformed(v, 1) += 0.8 * Hairpin::kGap;  // 0.2 gap from the first leg, 0.8 from its own
    }
    const Eigen::MatrixX3d closest = closest_counterparts(deformed, pin.mesh);
    for (const Eigen::Index v : facing) {
        ASSERT_GT(closest(v, 1), 0) << "the closest point of vertex " << v << " is on its own leg";
    }
    const Counterparts found = intrinsic_counterparts(pin.basis, pin.basis, pin.mesh, deformed, {});
    int home = 0;
    for (const Eigen::Index v : facing) {
        home += found.points.row(v) == pin.mesh.V.row(v) ? 1 : 0;
    }
    EXPECT_GE(home, static_cast<int>(0.95 * static_cast<double>(facing.size())));
    int unmoved = 0;
    for (Eigen::Index v = 0; v < pin.mesh.V.rows(); ++v) {
        unmoved += found.points.row(v) == pin.mesh.V.row(v) ? 1 : 0;
    }
    EXPECT_GE(unmoved, static_cast<int>(0.99 * static_cast<double>(pin.mesh.V.rows())));
    EXPECT_GE(found.moved, home);
}

// A reach far below the displacement keeps the counterparts where the match put them.
TEST(Counterparts, StayNearWhereTheMatchPutTheVertices) {
    const Hairpin pin;
    Eigen::MatrixX3d deformed = pin.mesh.V;
    for (const Eigen::Index v : pin.facing_vertices()) {
        deformed(v, 1) += 0.8 * Hairpin::kGap;
    }
    const Counterparts found = intrinsic_counterparts(pin.basis, pin.basis, pin.mesh, deformed,
                                                      {.enabled = true, .reach = 1e-4});
    const Eigen::MatrixX3d closest = closest_counterparts(deformed, pin.mesh);
    EXPECT_LT((found.points - closest).rowwise().norm().maxCoeff(), 0.2);  // an edge's length
    EXPECT_EQ(found.moved, 0);
}

TEST(Counterparts, DoNotDependOnTheSize) {
    const Hairpin pin;
    Eigen::MatrixX3d deformed = pin.mesh.V;
    for (const Eigen::Index v : pin.facing_vertices()) {
        deformed(v, 1) += 0.8 * Hairpin::kGap;
    }
    constexpr double kScale = 1000;
    TriangleMesh large = pin.mesh;
    large.V *= kScale;
    const LaplacianEigenbasis large_basis = laplacian_eigenbasis(large, kFunctions);
    const Counterparts found = intrinsic_counterparts(pin.basis, pin.basis, pin.mesh, deformed, {});
    const Counterparts scaled =
        intrinsic_counterparts(large_basis, large_basis, large, kScale * deformed, {});
    EXPECT_EQ(scaled.moved, found.moved);
    EXPECT_LT((scaled.points / kScale - found.points).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(Counterparts, RefuseBasesThatDoNotFitAndABadReach) {
    const Hairpin pin;
    const TriangleMesh other = hairpin(0.3);
    EXPECT_THROW((void)intrinsic_counterparts(pin.basis, pin.basis, other, other.V, {}),
                 InvalidInput);
    for (const double reach : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::infinity()}) {
        EXPECT_THROW((void)intrinsic_counterparts(pin.basis, pin.basis, pin.mesh, pin.mesh.V,
                                                  {.enabled = true, .reach = reach}),
                     InvalidInput)
            << reach;
    }
}

// The search near each query's position finds what a search of every target row finds
// (nearest_rows() of the weighted rows), whether the positions weigh much (a few rows near
// each query) or little (the bound takes in most rows), and from any previous rows.
TEST(NearestInJointEmbedding, FindsWhatASearchOfEveryRowFinds) {
    std::mt19937_64 random(7);
    std::normal_distribution<double> normal;
    const auto random_matrix = [&](Eigen::Index rows, Eigen::Index cols) {
        return Eigen::MatrixXd(
            Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return normal(random); }));
    };
    constexpr Eigen::Index kQueries = 300;
    constexpr Eigen::Index kTargets = 500;
    constexpr Eigen::Index kColumns = 12;
    const Eigen::MatrixX3d query_places = random_matrix(kQueries, 3);
    const Eigen::MatrixX3d target_places = random_matrix(kTargets, 3);
    const JointEmbedding queries{random_matrix(kQueries, kColumns), query_places};
    const JointEmbedding targets{random_matrix(kTargets, kColumns), target_places};
    const PointIndex index(target_places);
    std::uniform_int_distribution<Eigen::Index> any_target(0, kTargets - 1);
    std::vector<Eigen::Index> previous(kQueries);
    for (Eigen::Index& row : previous) {
        row = any_target(random);
    }
    for (const double weight : {0.1, 1.0, 30.0}) {
        Eigen::MatrixXd from(kQueries, kColumns + 3);
        from << queries.functions, weight * query_places;
        Eigen::MatrixXd to(kTargets, kColumns + 3);
        to << targets.functions, weight * target_places;
        const std::vector<Eigen::Index> everywhere = nearest_rows(from, to);
        EXPECT_EQ(nearest_in_joint_embedding(queries, targets, weight, index, previous), everywhere)
            << weight;
        EXPECT_EQ(nearest_in_joint_embedding(queries, targets, weight, index, everywhere),
                  everywhere)
            << weight;
    }
    EXPECT_THROW((void)nearest_in_joint_embedding(queries, targets, 0, index, previous),
                 InvalidInput);
}

}  // namespace
}  // namespace genflow::detail
