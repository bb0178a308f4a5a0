// SPDX-License-Identifier: MIT
#include "genflow/operators/laplacian_eigenbasis.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

TEST(LaplacianEigenbasis, SolvesTheGeneralizedProblemWithMOrthonormalFunctions) {
    for (const TriangleMesh& mesh :
         {test::noisy_icosphere(2, 0.3), test::noisy_torus(12, 6, 0.2), test::jittered_grid(6)}) {
        const LaplacianEigenbasis basis = laplacian_eigenbasis(mesh);
        const Eigen::VectorXd m = lumped_masses(mesh, MassType::Barycentric);
        const Eigen::SparseMatrix<double> K = cotan_stiffness(mesh);
        ASSERT_EQ(basis.values.size(), mesh.V.rows());
        ASSERT_EQ(basis.functions.cols(), mesh.V.rows());
        EXPECT_LT((basis.masses - m).cwiseAbs().maxCoeff(), 1e-15 * m.sum());
        const Eigen::MatrixXd gram = basis.functions.transpose() * m.asDiagonal() * basis.functions;
        EXPECT_LT(
            (gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff(),
            1e-9);
        // K φ = λ M φ, relative to the largest eigenvalue's scale.
        const Eigen::MatrixXd residual =
            K * basis.functions - m.asDiagonal() * basis.functions * basis.values.asDiagonal();
        EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-9 * basis.values.maxCoeff() * m.maxCoeff());
        // Ascending from λ_0 = 0 with a constant function (a connected mesh).
        EXPECT_NEAR(basis.values[0], 0, 1e-9 * basis.values.maxCoeff());
        EXPECT_GT(basis.values[1], 1e-6 * basis.values.maxCoeff());
        for (Eigen::Index k = 1; k < basis.values.size(); ++k) {
            EXPECT_LE(basis.values[k - 1], basis.values[k]);
        }
        const Eigen::VectorXd constant = basis.functions.col(0);
        EXPECT_LT((constant.array() - constant.mean()).abs().maxCoeff(),
                  1e-9 * std::abs(constant.mean()));
    }
}

// On a sphere of radius R the eigenvalues are l(l + 1)/R² with multiplicity 2l + 1.
TEST(LaplacianEigenbasis, HasTheSphericalHarmonicsSpectrumOnASphere) {
    const double radius = 2;
    const LaplacianEigenbasis basis = laplacian_eigenbasis(make_icosphere(3, radius));
    Eigen::Index k = 1;
    for (int l = 1; l <= 3; ++l) {
        const double exact = l * (l + 1) / (radius * radius);
        for (int copy = 0; copy < 2 * l + 1; ++copy, ++k) {
            // Measured within 1.5 % (642 vertices; l = 3 is the least accurate).
            EXPECT_NEAR(basis.values[k] / exact, 1, 0.02) << "l = " << l << ", k = " << k;
        }
    }
    // The next band starts at l = 4: 20/R², clearly above 12/R².
    EXPECT_GT(basis.values[k] * radius * radius, 18);
}

TEST(LaplacianEigenbasis, LeavesZeroMassVerticesOutAndRejectsBadInput) {
    TriangleMesh mesh = test::noisy_icosphere(1, 0.1);
    mesh.V.conservativeResize(mesh.V.rows() + 1, 3);
    mesh.V.row(mesh.V.rows() - 1) = Eigen::RowVector3d(5, 5, 5);  // referenced by no face
    const LaplacianEigenbasis basis = laplacian_eigenbasis(mesh);
    EXPECT_EQ(basis.values.size(), mesh.V.rows() - 1);
    EXPECT_EQ(basis.functions.row(mesh.V.rows() - 1).cwiseAbs().maxCoeff(), 0);

    EXPECT_THROW((void)laplacian_eigenbasis(make_icosphere(5)), InvalidInput);  // 10242 > 4000
    TriangleMesh flat = mesh;
    flat.V.setZero();
    EXPECT_THROW((void)laplacian_eigenbasis(flat), InvalidInput);
    TriangleMesh broken = mesh;
    broken.V(0, 0) = std::nan("");
    EXPECT_THROW((void)laplacian_eigenbasis(broken), InvalidInput);
}

// The lowest eigenpairs by Lanczos agree with the dense solve: values to rounding, functions up
// to sign where the eigenvalue is simple (a noisy torus has no symmetry left).
TEST(LaplacianEigenbasis, LowestPairsAgreeWithTheDenseSolve) {
    const TriangleMesh mesh = test::noisy_torus(40, 20, 0.2);  // 800 vertices: Lanczos
    const LaplacianEigenbasis full = laplacian_eigenbasis(mesh);
    const Eigen::Index count = 30;
    const LaplacianEigenbasis lowest = laplacian_eigenbasis(mesh, count);
    ASSERT_EQ(lowest.values.size(), count);
    ASSERT_EQ(lowest.functions.cols(), count);
    ASSERT_EQ(lowest.functions.rows(), mesh.V.rows());
    EXPECT_EQ(lowest.masses, full.masses);
    for (Eigen::Index k = 0; k < count; ++k) {
        EXPECT_NEAR(lowest.values[k], full.values[k], 1e-8 * full.values[count]) << "k = " << k;
        const double gap = std::min(k > 0 ? full.values[k] - full.values[k - 1] : 1e300,
                                    full.values[k + 1] - full.values[k]);
        if (gap > 1e-3 * full.values[count]) {
            const double overlap = std::abs(
                lowest.functions.col(k).dot(full.masses.asDiagonal() * full.functions.col(k)));
            EXPECT_NEAR(overlap, 1, 1e-6) << "k = " << k;
        }
    }
}

// A mesh the dense solve refuses: M-orthonormal pairs of K φ = λ M φ, and on a sphere the
// spherical harmonics' l(l + 1)/R² with multiplicity 2l + 1.
TEST(LaplacianEigenbasis, LowestPairsOfALargeMeshSolveTheProblem) {
    const double radius = 3;
    const TriangleMesh sphere = make_icosphere(5, radius);  // 10242 vertices
    const Eigen::Index count = 25;                          // l = 0 ... 4
    const LaplacianEigenbasis basis = laplacian_eigenbasis(sphere, count);
    const Eigen::VectorXd m = lumped_masses(sphere, MassType::Barycentric);
    const Eigen::SparseMatrix<double> K = cotan_stiffness(sphere);
    const Eigen::MatrixXd gram = basis.functions.transpose() * m.asDiagonal() * basis.functions;
    EXPECT_LT((gram - Eigen::MatrixXd::Identity(count, count)).cwiseAbs().maxCoeff(), 1e-8);
    const Eigen::MatrixXd residual =
        K * basis.functions - m.asDiagonal() * basis.functions * basis.values.asDiagonal();
    EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-8 * basis.values.maxCoeff() * m.maxCoeff());
    EXPECT_NEAR(basis.values[0], 0, 1e-9 * basis.values.maxCoeff());
    Eigen::Index k = 1;
    for (int l = 1; l <= 4; ++l) {
        const double exact = l * (l + 1) / (radius * radius);
        for (int copy = 0; copy < 2 * l + 1; ++copy, ++k) {
            // Measured within 0.2 % (10242 vertices; l = 4 the least accurate).
            EXPECT_NEAR(basis.values[k] / exact, 1, 0.005) << "l = " << l << ", k = " << k;
        }
    }
}

TEST(LaplacianEigenbasis, LowestPairsOfSmallMeshesAndBadCounts) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.1);  // 42 vertices: dense, truncated
    const LaplacianEigenbasis full = laplacian_eigenbasis(mesh);
    const LaplacianEigenbasis lowest = laplacian_eigenbasis(mesh, 5);
    ASSERT_EQ(lowest.values.size(), 5);
    EXPECT_EQ(lowest.values, full.values.head(5));
    EXPECT_EQ(lowest.functions, full.functions.leftCols(5));
    EXPECT_EQ(laplacian_eigenbasis(mesh, 1000).values.size(), mesh.V.rows());  // capped
    EXPECT_THROW((void)laplacian_eigenbasis(mesh, 0), InvalidInput);
    TriangleMesh broken = mesh;
    broken.V(0, 0) = std::nan("");
    EXPECT_THROW((void)laplacian_eigenbasis(broken, 5), InvalidInput);
}

}  // namespace
}  // namespace genflow
