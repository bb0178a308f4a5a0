// SPDX-License-Identifier: MIT
#include "genflow/metrics/volume_controlled_metric.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "genflow/energies/surface_area_energy.h"
#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/metrics/l2_metric.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/volume.h"
#include "genflow/smoothing/smoothing.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// Column j of the dense 3n×3n matrix of `op`, in the column-major flattening of fields.
template <typename Op>
Eigen::MatrixXd dense_matrix(Eigen::Index n, const Op& op) {
    Eigen::MatrixXd matrix(3 * n, 3 * n);
    for (Eigen::Index j = 0; j < 3 * n; ++j) {
        VertexField unit = VertexField::Zero(n, 3);
        unit(j % n, j / n) = 1.0;
        const VertexField column = op(unit);
        matrix.col(j) = Eigen::Map<const Eigen::VectorXd>(column.data(), column.size());
    }
    return matrix;
}

TEST(VolumeControlledMetric, GIsSymmetricPositiveDefiniteWithSpectrumBetweenDAndDOverLambda) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.2);
    const double lambda = 0.1;
    VolumeControlledMetric metric({.lambda = lambda});
    metric.update(mesh);
    const Eigen::Index n = mesh.V.rows();
    const Eigen::MatrixXd G =
        dense_matrix(n, [&](const VertexField& u) { return metric.apply(u); });
    EXPECT_LT((G - G.transpose()).norm(), 1e-8 * G.norm());
    // Generalized eigenvalues of (G, D) are those of L_VP: in [1, 1/λ].
    const Eigen::VectorXd m = lumped_masses(mesh, MassType::Barycentric);
    Eigen::VectorXd d(3 * n);
    d << m, m, m;
    const Eigen::MatrixXd scaled =
        d.cwiseSqrt().cwiseInverse().asDiagonal() * G * d.cwiseSqrt().cwiseInverse().asDiagonal();
    const Eigen::VectorXd eigenvalues =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (scaled + scaled.transpose()))
            .eigenvalues();
    EXPECT_GT(eigenvalues.minCoeff(), 1 - 1e-8);
    EXPECT_LT(eigenvalues.maxCoeff(), 1 / lambda + 1e-6);
    EXPECT_GT(eigenvalues.maxCoeff(), 2.0);  // the penalty is felt
}

TEST(VolumeControlledMetric, GradientInvertsApply) {
    const TriangleMesh mesh = test::noisy_torus(16, 8, 0.2);
    VolumeControlledMetric metric({.lambda = 0.05});
    metric.update(mesh);
    const VertexField U = test::random_matrix(mesh.V.rows(), 3, 1);
    EXPECT_LT(test::relative_error(metric.gradient(metric.apply(U)), U), 1e-8);
    EXPECT_LT(test::relative_error(metric.apply(metric.gradient(U)), U), 1e-8);
}

// A metric without halves to factor runs update_alongside()'s task after the update: once, or
// not at all when there is none, and the update is update()'s.
TEST(VolumeControlledMetric, UpdateAlongsideRunsTheTaskAfterTheUpdate) {
    const TriangleMesh mesh = test::noisy_torus(16, 8, 0.2);
    const VertexField U = test::random_matrix(mesh.V.rows(), 3, 2);
    VolumeControlledMetric metric({.lambda = 0.05});
    metric.update(mesh);
    const VertexField gradient = metric.gradient(U);
    int runs = 0;
    metric.update_alongside(mesh, [&runs] { ++runs; });
    EXPECT_EQ(runs, 1);
    EXPECT_EQ(metric.gradient(U), gradient);
    metric.update_alongside(mesh, {});
    EXPECT_EQ(metric.gradient(U), gradient);
}

TEST(VolumeControlledMetric, ProjectionIsDSelfAdjointWithSpectrumInZeroOne) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.2);
    VolumeControlledMetric metric;
    metric.update(mesh);
    const Eigen::Index n = mesh.V.rows();
    const Eigen::MatrixXd P =
        dense_matrix(n, [&](const VertexField& u) { return metric.volume_changing_part(u); });
    const Eigen::VectorXd m = lumped_masses(mesh, MassType::Barycentric);
    Eigen::VectorXd d(3 * n);
    d << m, m, m;
    const Eigen::MatrixXd DP = d.asDiagonal() * P;
    EXPECT_LT((DP - DP.transpose()).norm(), 1e-12 * DP.norm());
    const Eigen::MatrixXd S =
        d.cwiseSqrt().asDiagonal() * P * d.cwiseSqrt().cwiseInverse().asDiagonal();
    const Eigen::VectorXd eigenvalues =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (S + S.transpose())).eigenvalues();
    EXPECT_GT(eigenvalues.minCoeff(), -1e-12);
    EXPECT_LT(eigenvalues.maxCoeff(), 1 + 1e-12);
    // Uniform inflation (constant normal speed) lies in its range: eigenvalue 1.
    const VertexField inflation = metric.volume_changing_part(mesh.V.rowwise().normalized());
    EXPECT_GT(inflation.norm(), 0.9 * mesh.V.rowwise().normalized().norm());
}

TEST(VolumeControlledMetric, LambdaOneIsTheLumpedL2Metric) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.2);
    VolumeControlledMetric volume({.lambda = 1.0});
    L2Metric l2;
    volume.update(mesh);
    l2.update(mesh);
    const VertexField dEdX = SurfaceAreaEnergy{}.differential(mesh);
    EXPECT_LT(test::relative_error(volume.gradient(dEdX), l2.gradient(dEdX)), 1e-12);
    const Eigen::SparseMatrix<double> K = cotan_stiffness(mesh);
    EXPECT_LT(test::relative_error(volume.shifted_gradient(K, 0.01, dEdX),
                                   l2.shifted_gradient(K, 0.01, dEdX)),
              1e-8);
}

TEST(VolumeControlledMetric, ShiftedGradientSolvesTheImplicitSystem) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.2);
    VolumeControlledMetric metric({.lambda = 0.05});
    metric.update(mesh);
    const Eigen::SparseMatrix<double> K = cotan_stiffness(mesh);
    const VertexField R = SurfaceAreaEnergy{}.differential(mesh);
    const double dt = 0.05;
    const VertexField y = metric.shifted_gradient(K, dt, R);
    EXPECT_LT(test::relative_error(metric.apply(y) + dt * (K * y), R), 1e-8);
    EXPECT_LT(metric.last_iterations(), 100);
    // With vertices held, the system holds on the free rows and the held ones do not move.
    std::vector<bool> fixed(static_cast<std::size_t>(mesh.V.rows()), false);
    fixed[0] = fixed[7] = fixed[20] = true;
    metric.set_fixed_vertices(fixed);
    metric.update(mesh);
    VertexField held = metric.shifted_gradient(K, dt, R);
    for (const int i : {0, 7, 20}) {
        EXPECT_EQ(held.row(i).norm(), 0.0);
    }
    VertexField residual = metric.apply(held) + dt * (K * held) - R;
    VertexField free_rhs = R;
    for (const int i : {0, 7, 20}) {
        residual.row(i).setZero();
        free_rhs.row(i).setZero();
    }
    EXPECT_LT(residual.norm(), 1e-8 * free_rhs.norm());
}

TEST(VolumeControlledMetric, VolumeLossShrinksWithLambdaAndIgnoresOrientation) {
    const TriangleMesh noisy = test::noisy_torus(48, 20, 0.3, 4);
    const double volume = enclosed_volume(noisy);
    const SmoothingOptions base{.time_step = 5.0, .steps = 5};
    const double plain_loss = volume - enclosed_volume(implicit_fairing(noisy, base).mesh);
    EXPECT_GT(plain_loss, 0);
    double previous = plain_loss;
    for (const double lambda : {0.3, 0.05, 0.01}) {
        SmoothingOptions options = base;
        options.volume_lambda = lambda;
        const FlowResult result = volume_controlled_fairing(noisy, options);
        ASSERT_TRUE(result.ok()) << result.message;
        const double loss = std::abs(volume - enclosed_volume(result.mesh));
        EXPECT_LT(loss, previous) << "lambda " << lambda;
        previous = loss;
    }
    EXPECT_LT(previous, 0.1 * plain_loss);
    // Flipped faces: the same motion, so the volume shrinks in magnitude the same way.
    TriangleMesh flipped = noisy;
    flipped.F.col(1).swap(flipped.F.col(2));
    SmoothingOptions options = base;
    options.volume_lambda = 0.01;
    const FlowResult a = volume_controlled_fairing(noisy, options);
    const FlowResult b = volume_controlled_fairing(flipped, options);
    EXPECT_LT(test::relative_error(b.mesh.V, a.mesh.V), 1e-8);
}

TEST(VolumeControlledMetric, GradientStepDecreasesTheAreaAndFixedVerticesStay) {
    const TriangleMesh mesh = test::jittered_grid(8);
    TriangleMesh bumpy = add_noise(mesh, 0.02, 6);
    VolumeControlledMetric metric({.lambda = 0.05});
    std::vector<bool> fixed(static_cast<std::size_t>(mesh.V.rows()), false);
    fixed[0] = fixed[40] = true;
    metric.set_fixed_vertices(fixed);
    metric.update(bumpy);
    const SurfaceAreaEnergy area;
    const VertexField dEdX = area.differential(bumpy);
    const VertexField g = metric.gradient(dEdX);
    EXPECT_GT((dEdX.array() * g.array()).sum(), 0);
    EXPECT_EQ(g.row(0).norm(), 0.0);
    EXPECT_EQ(g.row(40).norm(), 0.0);
    const VertexField s = metric.shifted_gradient(cotan_stiffness(bumpy), 0.01, dEdX);
    EXPECT_EQ(s.row(40).norm(), 0.0);
    TriangleMesh moved = bumpy;
    moved.V -= 1e-3 * g / g.norm();
    EXPECT_LT(area.value(moved), area.value(bumpy));
}

TEST(VolumeControlledMetric, RejectsBadParameters) {
    EXPECT_THROW(VolumeControlledMetric({.lambda = 0}), InvalidInput);
    EXPECT_THROW(VolumeControlledMetric({.lambda = 1.5}), InvalidInput);
    EXPECT_THROW(VolumeControlledMetric({.lambda = 0.1, .tolerance = 0}), InvalidInput);
    VolumeControlledMetric metric;
    EXPECT_THROW((void)metric.gradient(VertexField::Zero(3, 3)), InvalidInput);
}

}  // namespace
}  // namespace genflow
