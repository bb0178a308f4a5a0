// SPDX-License-Identifier: MIT
#include "genflow/operators/laplacian_eigenbasis.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace genflow
