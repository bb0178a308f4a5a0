// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <memory>

#include "genflow/energies/edge_length_energy.h"
#include "genflow/energies/enclosed_volume_energy.h"
#include "genflow/energies/landmark_energy.h"
#include "genflow/energies/surface_area_energy.h"
#include "genflow/energies/weighted_sum_energy.h"
#include "genflow/exceptions.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

void expect_differential_matches_finite_differences(const Energy& energy,
                                                    const TriangleMesh& mesh) {
    const VertexField fd = test::finite_difference_gradient(
        [&](const TriangleMesh& m) { return energy.value(m); }, mesh);
    EXPECT_LT(test::relative_error(energy.differential(mesh), fd), 1e-6);
}

TEST(Energies, DifferentialsMatchCentralFiniteDifferences) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.2);
    expect_differential_matches_finite_differences(SurfaceAreaEnergy{}, mesh);
    expect_differential_matches_finite_differences(EnclosedVolumeEnergy{}, mesh);
    const WeightedSumEnergy sum({{2.0, std::make_shared<SurfaceAreaEnergy>()},
                                 {-0.5, std::make_shared<EnclosedVolumeEnergy>()}});
    expect_differential_matches_finite_differences(sum, mesh);
    EXPECT_NEAR(sum.value(mesh),
                2 * SurfaceAreaEnergy{}.value(mesh) - 0.5 * EnclosedVolumeEnergy{}.value(mesh),
                1e-12);
}

TEST(Energies, AreaLinearizationReproducesTheDifferential) {
    const TriangleMesh mesh = test::noisy_torus(12, 6, 0.2);
    const SurfaceAreaEnergy area;
    const auto linearization = area.linearize(mesh);
    ASSERT_TRUE(linearization);
    EXPECT_LT(
        test::relative_error(linearization->A * mesh.V + linearization->B, area.differential(mesh)),
        1e-12);
}

TEST(Energies, WeightedSumLinearizesOnlyWithPositiveLinearizableTerms) {
    const TriangleMesh mesh = test::noisy_icosphere(1);
    const auto area = std::make_shared<SurfaceAreaEnergy>();
    const auto volume = std::make_shared<EnclosedVolumeEnergy>();
    const auto sum = WeightedSumEnergy({{3.0, area}, {0.0, volume}}).linearize(mesh);
    ASSERT_TRUE(sum);
    EXPECT_LT(test::relative_error(sum->A * mesh.V, 3.0 * area->differential(mesh)), 1e-12);
    EXPECT_FALSE(WeightedSumEnergy({{1.0, area}, {1.0, volume}}).linearize(mesh));
    EXPECT_FALSE(WeightedSumEnergy({{-1.0, area}}).linearize(mesh));
    EXPECT_FALSE(EnclosedVolumeEnergy{}.linearize(mesh));
    EXPECT_THROW(WeightedSumEnergy({{NAN, area}}), InvalidInput);
    EXPECT_THROW(WeightedSumEnergy({{1.0, nullptr}}), InvalidInput);
}

TEST(EdgeLengthEnergy, VanishesUnderRigidMotionAndMeasuresUniformScaling) {
    const TriangleMesh rest = test::noisy_icosphere(2, 0.2);
    const EdgeLengthEnergy energy(rest);
    EXPECT_EQ(energy.value(rest), 0);
    EXPECT_LT(energy.differential(rest).cwiseAbs().maxCoeff(), 1e-15);

    TriangleMesh moved = rest;
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
    moved.V = (rest.V * rotation.transpose()).rowwise() + Eigen::RowVector3d(3, -1, 2);
    EXPECT_LT(energy.value(moved), 1e-28);

    // Every edge s times longer: Σ (s − 1)² ℓ² / Σ ℓ² = (s − 1)².
    for (const double s : {0.5, 1.1, 3.0}) {
        moved.V = s * rest.V;
        EXPECT_NEAR(energy.value(moved), (s - 1) * (s - 1), 1e-12);
    }
}

TEST(EdgeLengthEnergy, IsFreeToBendAlongAnEdge) {
    // Two triangles folded about their shared edge keep every length.
    TriangleMesh hinge;
    hinge.V.resize(4, 3);
    hinge.V << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0;
    hinge.F.resize(2, 3);
    hinge.F << 0, 1, 2, 1, 0, 3;
    const EdgeLengthEnergy energy(hinge);
    TriangleMesh folded = hinge;
    folded.V.row(3) << 0.5, -std::cos(1.0), std::sin(1.0);
    EXPECT_LT(energy.value(folded), 1e-30);
    folded.V.row(3) << 0.5, -1.5, 0;  // two edges stretched to √(0.25 + 2.25)
    const double stretch = std::sqrt(2.5) - std::sqrt(1.25);
    EXPECT_NEAR(energy.value(folded), 2 * stretch * stretch / (1 + 4 * 1.25), 1e-14);
}

TEST(EdgeLengthEnergy, DifferentialAndLinearizationAgreeWithTheValue) {
    const TriangleMesh rest = test::noisy_torus(12, 6, 0.1);
    const EdgeLengthEnergy energy(rest);
    const TriangleMesh deformed = test::noisy_torus(12, 6, 0.3, 7);
    expect_differential_matches_finite_differences(energy, deformed);

    const auto linearization = energy.linearize(deformed);
    ASSERT_TRUE(linearization);
    EXPECT_LT(test::relative_error(linearization->A * deformed.V + linearization->B,
                                   energy.differential(deformed)),
              1e-12);
    const Eigen::SparseMatrix<double> A = linearization->A;
    EXPECT_EQ((Eigen::MatrixXd(A) - Eigen::MatrixXd(A).transpose()).cwiseAbs().maxCoeff(), 0);
    // A is a graph Laplacian: rows sum to zero, and it is PSD.
    EXPECT_LT((A * Eigen::VectorXd::Ones(A.cols())).cwiseAbs().maxCoeff(), 1e-12);
    const Eigen::VectorXd v = test::random_matrix(A.cols(), 1, 1);
    EXPECT_GT(v.dot(A * v), 0);
}

TEST(EdgeLengthEnergy, RefusesMismatchedAndDegenerateMeshes) {
    const TriangleMesh rest = test::noisy_icosphere(1);
    const EdgeLengthEnergy energy(rest);
    const TriangleMesh other = test::noisy_icosphere(2);
    EXPECT_THROW((void)energy.value(other), InvalidInput);
    EXPECT_THROW((void)energy.differential(other), InvalidInput);
    EXPECT_THROW((void)energy.linearize(other), InvalidInput);
    TriangleMesh collapsed = rest;
    collapsed.V.setZero();
    EXPECT_THROW(EdgeLengthEnergy{collapsed}, InvalidInput);
    TriangleMesh broken = rest;
    broken.V(0, 0) = NAN;
    EXPECT_THROW(EdgeLengthEnergy{broken}, InvalidInput);
    broken = rest;
    broken.F(0, 0) = static_cast<int>(rest.V.rows());
    EXPECT_THROW(EdgeLengthEnergy{broken}, InvalidInput);
}

TEST(LandmarkEnergy, IsTheMeanSquaredDistanceInUnitsOfTheLength) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.2);
    Eigen::MatrixX3d points(3, 3);
    points.row(0) = mesh.V.row(4) + Eigen::RowVector3d(0.3, 0, 0);
    points.row(1) = mesh.V.row(7) + Eigen::RowVector3d(0, 0, -0.4);
    points.row(2) = mesh.V.row(4);  // a second landmark on vertex 4
    const LandmarkEnergy energy(mesh.V.rows(), {4, 7, 4}, points, 2.0);
    // (0.3² + 0.4² + 0) / (3 · 2²): vertex 4 lies 0.3 from one of its points and on the other.
    EXPECT_NEAR(energy.value(mesh), (0.09 + 0.16) / 12, 1e-15);
    TriangleMesh moved = mesh;
    moved.V.row(7) = points.row(1);
    moved.V.row(4) = 0.5 * (points.row(0) + points.row(2));  // the two points' midpoint
    EXPECT_NEAR(energy.value(moved), (0.0225 + 0.0225) / 12, 1e-15);
    expect_differential_matches_finite_differences(energy, mesh);
    // At the midpoint the two landmarks of vertex 4 pull it both ways alike.
    EXPECT_LT(energy.differential(moved).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(LandmarkEnergy, AWeightCountsAsThatManyCopiesOfItsLandmark) {
    const TriangleMesh mesh = test::noisy_torus(12, 6, 0.2);
    const Eigen::MatrixX3d points = test::random_matrix(2, 3, 8);
    Eigen::MatrixX3d copies(4, 3);
    copies << points.row(0), points.row(1), points.row(1), points.row(1);
    const LandmarkEnergy weighted(mesh.V.rows(), {2, 11}, points, 0.8, Eigen::Vector2d(1, 3));
    const LandmarkEnergy repeated(mesh.V.rows(), {2, 11, 11, 11}, copies, 0.8);
    // (|x_2 − y_0|² + 3 |x_11 − y_1|²) / (4 · 0.8²), as the four landmarks alike.
    const double expected = ((mesh.V.row(2) - points.row(0)).squaredNorm() +
                             3 * (mesh.V.row(11) - points.row(1)).squaredNorm()) /
                            (4 * 0.64);
    EXPECT_NEAR(weighted.value(mesh), expected, 1e-14 * expected);
    EXPECT_NEAR(repeated.value(mesh), expected, 1e-14 * expected);
    EXPECT_LT(test::relative_error(weighted.differential(mesh), repeated.differential(mesh)),
              1e-14);
    expect_differential_matches_finite_differences(weighted, mesh);
    // The copies' linearization is exact (below), so the weighted one is where they agree.
    const auto by_weight = weighted.linearize(mesh);
    const auto by_copies = repeated.linearize(mesh);
    ASSERT_TRUE(by_weight && by_copies);
    EXPECT_LT((Eigen::MatrixXd(by_weight->A) - Eigen::MatrixXd(by_copies->A)).norm(),
              1e-14 * Eigen::MatrixXd(by_copies->A).norm());
    EXPECT_LT(test::relative_error(by_weight->B, by_copies->B), 1e-14);
}

TEST(LandmarkEnergy, LinearizationIsExactAndPositiveSemiDefinite) {
    const TriangleMesh mesh = test::noisy_torus(12, 6, 0.2);
    const Eigen::MatrixX3d points = test::random_matrix(3, 3, 5);
    const LandmarkEnergy energy(mesh.V.rows(), {0, 9, 0}, points, 0.7);
    const auto linearization = energy.linearize(mesh);
    ASSERT_TRUE(linearization);
    // Exact at any positions, not just the ones it was taken at (E is quadratic).
    const TriangleMesh other = test::noisy_torus(12, 6, 0.4, 3);
    EXPECT_LT(test::relative_error(linearization->A * other.V + linearization->B,
                                   energy.differential(other)),
              1e-12);
    // Diagonal, positive on the landmarks' vertices alone: two landmarks on vertex 0, one on 9.
    EXPECT_EQ(linearization->A.nonZeros(), 2);
    const Eigen::MatrixXd A(linearization->A);
    EXPECT_GT(A(9, 9), 0);
    EXPECT_NEAR(A(0, 0), 2 * A(9, 9), 1e-15);
    EXPECT_EQ(A.diagonal().sum(), A(0, 0) + A(9, 9));
}

TEST(LandmarkEnergy, RefusesWhatItCannotUse) {
    const TriangleMesh mesh = test::noisy_icosphere(1);
    const Eigen::MatrixX3d one = Eigen::MatrixX3d::Zero(1, 3);
    EXPECT_THROW(LandmarkEnergy(mesh.V.rows(), {}, Eigen::MatrixX3d(0, 3), 1), InvalidInput);
    EXPECT_THROW(LandmarkEnergy(mesh.V.rows(), {0, 1}, one, 1), InvalidInput);
    EXPECT_THROW(LandmarkEnergy(mesh.V.rows(), {mesh.V.rows()}, one, 1), InvalidInput);
    EXPECT_THROW(LandmarkEnergy(mesh.V.rows(), {-1}, one, 1), InvalidInput);
    EXPECT_THROW(LandmarkEnergy(mesh.V.rows(), {0}, one, 0), InvalidInput);
    EXPECT_THROW(LandmarkEnergy(mesh.V.rows(), {0}, one, NAN), InvalidInput);
    Eigen::MatrixX3d bad = one;
    bad(0, 1) = INFINITY;
    EXPECT_THROW(LandmarkEnergy(mesh.V.rows(), {0}, bad, 1), InvalidInput);
    EXPECT_THROW(LandmarkEnergy(mesh.V.rows(), {0}, one, 1, Eigen::VectorXd::Zero(1)),
                 InvalidInput);
    EXPECT_THROW(LandmarkEnergy(mesh.V.rows(), {0}, one, 1, Eigen::VectorXd::Constant(1, NAN)),
                 InvalidInput);
    EXPECT_THROW(LandmarkEnergy(mesh.V.rows(), {0}, one, 1, Eigen::VectorXd::Ones(2)),
                 InvalidInput);
    const LandmarkEnergy energy(mesh.V.rows(), {0}, one, 1);
    EXPECT_THROW((void)energy.value(test::noisy_icosphere(2)), InvalidInput);
    EXPECT_THROW((void)energy.differential(test::noisy_icosphere(2)), InvalidInput);
    EXPECT_THROW((void)energy.linearize(test::noisy_icosphere(2)), InvalidInput);
}

}  // namespace
}  // namespace genflow
