// SPDX-License-Identifier: MIT
// The prioritized subspace metric (docs/formulas.md §6) and the quasi-rigid prior (§5): G symmetric
// positive definite, gradient inverts apply, blocks M-orthonormal, rigid fields boosted by
// exactly 1/μ, the Woodbury implicit solve equals a dense one.
#include "genflow/metrics/subspace_metric.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/metrics/l2_metric.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/operators/mesh_size.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// G as a dense 3n×3n matrix, column by column from apply().
Eigen::MatrixXd dense_metric(const Metric& metric, Eigen::Index n) {
    Eigen::MatrixXd G(3 * n, 3 * n);
    for (Eigen::Index c = 0; c < 3 * n; ++c) {
        VertexField unit = VertexField::Zero(n, 3);
        unit(c / 3, c % 3) = 1;
        const VertexField column = metric.apply(unit);
        for (Eigen::Index i = 0; i < n; ++i) {
            G.block<3, 1>(3 * i, c) = column.row(i).transpose();
        }
    }
    return G;
}

// Blocks that overlap on purpose: the rigid blocks, then a "bend" block that repeats a rotation
// (about another centre) and adds a field of its own.
std::vector<FieldBlock> overlapping_blocks(const TriangleMesh& mesh, const Eigen::VectorXd& m) {
    std::vector<FieldBlock> blocks = rigid_motion_blocks(mesh, m, {});
    FieldBlock bend{Eigen::MatrixXd::Zero(3 * mesh.V.rows(), 2), 0.1};
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        const Eigen::Vector3d y = mesh.V.row(i).transpose() - Eigen::Vector3d(0.3, 0, 0);
        bend.fields.block<3, 1>(3 * i, 0) = Eigen::Vector3d::UnitZ().cross(y);
        bend.fields.block<3, 1>(3 * i, 1) =
            std::max(0.0, mesh.V(i, 0)) * Eigen::Vector3d::UnitX().cross(y);
    }
    blocks.push_back(bend);
    return blocks;
}

TEST(SubspaceMetric, IsSymmetricPositiveDefiniteAndInvertsApply) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.1);
    SubspaceMetric metric(overlapping_blocks);
    metric.update(mesh);
    const Eigen::MatrixXd G = dense_metric(metric, mesh.V.rows());
    EXPECT_LT((G - G.transpose()).norm(), 1e-12 * G.norm());
    const Eigen::VectorXd eigenvalues =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(G).eigenvalues();
    EXPECT_GT(eigenvalues.minCoeff(), 0);
    // The smallest eigenvalues are the boosted directions: μ·m_i scale, never below.
    EXPECT_GT(eigenvalues.minCoeff(), 1e-3 * 5e-3 * metric.masses().minCoeff());

    const VertexField U = test::noisy_icosphere(1, 0.3, 7).V;
    EXPECT_LT(test::relative_error(metric.gradient(metric.apply(U)), U), 1e-11);
    EXPECT_LT(test::relative_error(metric.apply(metric.gradient(U)), U), 1e-11);
}

TEST(SubspaceMetric, BlocksAreMOrthonormalAndDropSpannedDirections) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.1);
    SubspaceMetric metric(overlapping_blocks);
    metric.update(mesh);
    const auto& blocks = metric.orthonormal_blocks();
    ASSERT_EQ(blocks.size(), 4U);
    EXPECT_EQ(blocks[3].fields.cols(), 1);  // the repeated rotation is dropped
    Eigen::MatrixXd Q(3 * mesh.V.rows(), 0);
    for (const FieldBlock& block : blocks) {
        Eigen::MatrixXd grown(Q.rows(), Q.cols() + block.fields.cols());
        grown << Q, block.fields;
        Q = grown;
    }
    Eigen::MatrixXd MQ = Q;
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        MQ.middleRows(3 * i, 3) *= metric.masses()[i];
    }
    EXPECT_LT((Q.transpose() * MQ - Eigen::MatrixXd::Identity(Q.cols(), Q.cols())).norm(), 1e-12);
}

TEST(QuasiRigidMetric, BoostsRigidFieldsByOneOverThePenalty) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.2);
    const QuasiRigidOptions options{.translation = 0.01, .rotation = 0.02, .scaling = 0.5};
    SubspaceMetric metric = quasi_rigid_metric(options);
    metric.update(mesh);
    const Eigen::VectorXd& m = metric.masses();
    const Eigen::RowVector3d centre = (m.transpose() * mesh.V) / m.sum();
    // A rotation field about the M-centroid: its differential M·v comes back as v/μ_R.
    VertexField rotation(mesh.V.rows(), 3);
    const Eigen::Vector3d omega(0.3, -1, 0.5);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        rotation.row(i) = omega.cross((mesh.V.row(i) - centre).transpose()).transpose();
    }
    const VertexField dE = (rotation.array().colwise() * m.array()).matrix();
    EXPECT_LT(test::relative_error(metric.gradient(dE), rotation / options.rotation), 1e-12);
    // A translation: boosted by 1/μ_T.
    const VertexField shift = VertexField::Ones(mesh.V.rows(), 3);
    const VertexField dT = (shift.array().colwise() * m.array()).matrix();
    EXPECT_LT(test::relative_error(metric.gradient(dT), shift / options.translation), 1e-12);
}

// Issue 5's check: between a template and a rigidly moved copy (another sampling), the
// quasi-rigid gradient of d_H is almost a rigid motion, the L2 gradient is not.
TEST(QuasiRigidMetric, GradientTowardsARigidlyMovedCopyIsNearlyRigid) {
    const TriangleMesh template_mesh = make_limb(3);
    TriangleMesh target = make_limb(3, 7);
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(0.15, Eigen::Vector3d(1, 2, 2).normalized()).toRotationMatrix();
    target.V = (target.V * turn.transpose()).rowwise() + Eigen::RowVector3d(0.2, -0.1, 0.1);
    const PseudoHausdorffEnergy energy(target, {.alpha = 8, .epsilon = mean_edge_length(target)});
    const VertexField dE = energy.differential(template_mesh);
    SubspaceMetric rigid = quasi_rigid_metric();
    L2Metric l2;
    rigid.update(template_mesh);
    l2.update(template_mesh);
    // The share of a field (in the M norm) outside the span of translations, rotations and
    // the scaling (which the prior also makes cheap).
    const Eigen::VectorXd& m = rigid.masses();
    const std::vector<FieldBlock> blocks = rigid_motion_blocks(template_mesh, m, {});
    Eigen::MatrixXd basis(3 * template_mesh.V.rows(), 7);
    basis << blocks[0].fields, blocks[1].fields, blocks[2].fields;
    const Eigen::VectorXd weights = m.replicate(1, 3).transpose().reshaped();
    const auto non_rigid_share = [&](const VertexField& field) {
        const Eigen::VectorXd v = field.transpose().reshaped();
        const Eigen::MatrixXd Bw = basis.array().colwise() * weights.array();
        const Eigen::VectorXd coefficients =
            (basis.transpose() * Bw).ldlt().solve(Bw.transpose() * v);
        const Eigen::VectorXd rest = v - basis * coefficients;
        return std::sqrt(rest.dot(weights.cwiseProduct(rest)) / v.dot(weights.cwiseProduct(v)));
    };
    const double rigid_share = non_rigid_share(rigid.gradient(dE));
    const double l2_share = non_rigid_share(l2.gradient(dE));
    EXPECT_LT(rigid_share, 0.05) << rigid_share << " (L2: " << l2_share << ")";
    EXPECT_GT(l2_share, 10 * rigid_share);  // measured 0.017 against 0.95
}

TEST(QuasiRigidMetric, WithNeutralPenaltiesIsTheL2Metric) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.2);
    SubspaceMetric metric = quasi_rigid_metric({.translation = 1, .rotation = 1, .scaling = 1});
    L2Metric l2;
    metric.update(mesh);
    l2.update(mesh);
    const VertexField D = test::noisy_icosphere(2, 0.3, 5).V;
    EXPECT_LT(test::relative_error(metric.gradient(D), l2.gradient(D)), 1e-12);
}

// As 3n vectors (vertex i in entries 3i, 3i+1, 3i+2), and back.
Eigen::VectorXd flattened(const VertexField& field) {
    return field.transpose().reshaped();
}
VertexField unflattened(const Eigen::VectorXd& vector) {
    return vector.reshaped(3, vector.size() / 3).transpose();
}

// (G + dt·A)⁻¹ R by the metric's Woodbury solve against a dense solve, for a diagonal A and dt
// from 0 to 100, to `tolerance` relative error.
void expect_implicit_solve_matches_dense(SubspaceMetric& metric, const TriangleMesh& mesh,
                                         double tolerance) {
    metric.update(mesh);
    const Eigen::Index n = mesh.V.rows();
    Eigen::SparseMatrix<double> A(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
        A.insert(i, i) = 0.5 + static_cast<double>(i % 5);
    }
    const VertexField R = test::noisy_icosphere(1, 0.3, 11).V;
    for (const double dt : {0.0, 0.01, 1.0, 100.0}) {
        Eigen::MatrixXd system = dense_metric(metric, n);
        for (Eigen::Index i = 0; i < n; ++i) {
            system.block<3, 3>(3 * i, 3 * i).diagonal().array() += dt * A.coeff(i, i);
        }
        const Eigen::VectorXd expected = system.ldlt().solve(flattened(R));
        const VertexField solved = metric.shifted_gradient(A, dt, R);
        EXPECT_LT(test::relative_error(solved, unflattened(expected)), tolerance) << dt;
    }
}

TEST(SubspaceMetric, WoodburyImplicitSolveEqualsADenseSolve) {
    SubspaceMetric metric(overlapping_blocks);
    expect_implicit_solve_matches_dense(metric, test::noisy_icosphere(1, 0.1), 1e-10);
}

TEST(SubspaceMetric, OverAnH1BaseIsSPDBOrthonormalAndMeasuresTheResidualByB) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.1);
    const Eigen::Index n = mesh.V.rows();
    const SobolevOptions sobolev{.lambda = 0.05};
    SubspaceMetric metric(overlapping_blocks, {}, std::make_unique<H1Metric>(sobolev));
    H1Metric h1(sobolev);
    metric.update(mesh);
    h1.update(mesh);
    const Eigen::MatrixXd G = dense_metric(metric, n);
    const Eigen::MatrixXd B = dense_metric(h1, n);
    EXPECT_LT((G - G.transpose()).norm(), 1e-12 * G.norm());
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(G).eigenvalues().minCoeff(), 0);
    const VertexField U = test::noisy_icosphere(1, 0.3, 7).V;
    EXPECT_LT(test::relative_error(metric.gradient(metric.apply(U)), U), 1e-10);

    const std::vector<FieldBlock> blocks = metric.orthonormal_blocks();
    ASSERT_EQ(blocks.size(), 4U);
    Eigen::MatrixXd Q(3 * n, 0);
    for (const FieldBlock& block : blocks) {
        Eigen::MatrixXd grown(Q.rows(), Q.cols() + block.fields.cols());
        grown << Q, block.fields;
        Q = grown;
        // A block's motions cost μ times their B-norm.
        EXPECT_LT((G * block.fields - block.penalty * B * block.fields).norm(),
                  1e-10 * (B * block.fields).norm());
    }
    EXPECT_LT((Q.transpose() * B * Q - Eigen::MatrixXd::Identity(Q.cols(), Q.cols())).norm(),
              1e-10);
    // The residual, B-orthogonal to every block, costs its B-norm: G v = B v.
    const Eigen::VectorXd u = flattened(U);
    const Eigen::VectorXd residual = u - Q * (Q.transpose() * (B * u));
    EXPECT_LT((G * residual - B * residual).norm(), 1e-10 * (B * residual).norm());
    // ... which the L2 base does not: there, the same field costs its M-norm.
    SubspaceMetric over_mass(overlapping_blocks);
    over_mass.update(mesh);
    EXPECT_GT((dense_metric(over_mass, n) * residual - B * residual).norm(),
              0.1 * (B * residual).norm());
}

TEST(SubspaceMetric, OverAnH1BaseTheWoodburyImplicitSolveEqualsADenseSolve) {
    SubspaceMetric metric(overlapping_blocks, {},
                          std::make_unique<H1Metric>(SobolevOptions{.lambda = 0.05}));
    expect_implicit_solve_matches_dense(metric, test::noisy_icosphere(1, 0.1), 1e-9);
}

TEST(SubspaceMetric, RejectsBadInput) {
    const TriangleMesh mesh = make_icosphere(1);
    SubspaceMetric wrong_rows([](const TriangleMesh&, const Eigen::VectorXd&) {
        return std::vector<FieldBlock>{{Eigen::MatrixXd::Ones(5, 1), 0.1}};
    });
    EXPECT_THROW(wrong_rows.update(mesh), InvalidInput);
    SubspaceMetric bad_penalty([](const TriangleMesh& m, const Eigen::VectorXd&) {
        return std::vector<FieldBlock>{{Eigen::MatrixXd::Ones(3 * m.V.rows(), 1), 0.0}};
    });
    EXPECT_THROW(bad_penalty.update(mesh), InvalidInput);
    EXPECT_THROW((void)quasi_rigid_metric({.rotation = -1}), InvalidInput);

    SubspaceMetric metric = quasi_rigid_metric();
    EXPECT_THROW((void)metric.gradient(mesh.V), InvalidInput);  // before update()
    metric.set_fixed_vertices(std::vector<bool>(static_cast<std::size_t>(mesh.V.rows()), true));
    EXPECT_THROW(metric.update(mesh), InvalidInput);
    metric.set_fixed_vertices({});
    metric.update(mesh);
    Eigen::SparseMatrix<double> offdiagonal(mesh.V.rows(), mesh.V.rows());
    offdiagonal.insert(0, 1) = 1;
    EXPECT_THROW((void)metric.shifted_gradient(offdiagonal, 1, mesh.V), InvalidInput);

    // An update that throws leaves no metric of the one before: it refuses every field.
    auto calls = std::make_shared<int>(0);
    SubspaceMetric fails_later([calls](const TriangleMesh& m, const Eigen::VectorXd&) {
        const Eigen::Index rows = ++*calls == 1 ? 3 * m.V.rows() : 5;
        return std::vector<FieldBlock>{{Eigen::MatrixXd::Ones(rows, 1), 0.1}};
    });
    fails_later.update(mesh);
    EXPECT_NO_THROW((void)fails_later.gradient(mesh.V));
    EXPECT_THROW(fails_later.update(mesh), InvalidInput);
    EXPECT_THROW((void)fails_later.gradient(mesh.V), InvalidInput);
    EXPECT_THROW((void)fails_later.apply(mesh.V), InvalidInput);
}

}  // namespace
}  // namespace genflow
