// SPDX-License-Identifier: MIT
#include "genflow/operators/cotan_stiffness.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/area.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/normals.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

class CotanStiffnessOnMeshes : public ::testing::TestWithParam<int> {
protected:
    static TriangleMesh mesh_for(int which) {
        switch (which) {
            case 0:
                return test::noisy_icosphere(2);
            case 1:
                return test::noisy_torus(16, 8);
            default:
                return test::jittered_grid(6);
        }
    }
};

TEST_P(CotanStiffnessOnMeshes, IsSymmetricWithConstantsInNullSpace) {
    const TriangleMesh mesh = mesh_for(GetParam());
    const Eigen::SparseMatrix<double> K = cotan_stiffness(mesh);
    const Eigen::MatrixXd dense = K;
    EXPECT_LT((dense - dense.transpose()).cwiseAbs().maxCoeff(),
              1e-14 * dense.cwiseAbs().maxCoeff());
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(mesh.V.rows());
    EXPECT_LT((K * ones).cwiseAbs().maxCoeff(), 1e-12 * dense.cwiseAbs().maxCoeff());
}

TEST_P(CotanStiffnessOnMeshes, IsPositiveSemiDefinite) {
    const TriangleMesh mesh = mesh_for(GetParam());
    const Eigen::MatrixXd K = cotan_stiffness(mesh);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(K);
    const Eigen::VectorXd values = eigen.eigenvalues();
    EXPECT_GT(values.minCoeff(), -1e-12 * values.maxCoeff());
    EXPECT_LT(std::abs(values[0]), 1e-12 * values.maxCoeff());  // constants: the null space
    EXPECT_GT(values[1], 1e-6 * values.maxCoeff());             // connected: only one zero
}

TEST_P(CotanStiffnessOnMeshes, TimesPositionsIsTheAreaGradient) {
    const TriangleMesh mesh = mesh_for(GetParam());
    const VertexField KX = cotan_stiffness(mesh) * mesh.V;
    EXPECT_LT(test::relative_error(KX, surface_area_gradient(mesh)), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Meshes, CotanStiffnessOnMeshes, ::testing::Values(0, 1, 2));

TEST(CotanStiffness, LaplacianOfLinearFunctionVanishesAtInteriorVertices) {
    const TriangleMesh mesh = test::jittered_grid(8);
    const Eigen::SparseMatrix<double> K = cotan_stiffness(mesh);
    const Eigen::VectorXd f =
        2.0 * mesh.V.col(0) - 3.0 * mesh.V.col(1) + Eigen::VectorXd::Constant(mesh.V.rows(), 0.5);
    const Eigen::VectorXd Kf = K * f;
    int interior = 0;
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        const double x = mesh.V(i, 0);
        const double y = mesh.V(i, 1);
        if (x > 1e-9 && x < 1 - 1e-9 && y > 1e-9 && y < 1 - 1e-9) {
            EXPECT_NEAR(Kf[i], 0.0, 1e-12) << "vertex " << i;
            ++interior;
        }
    }
    EXPECT_EQ(interior, 49);
    // On the boundary it does not vanish: the check above is not vacuous.
    EXPECT_GT(Kf.cwiseAbs().maxCoeff(), 0.1);
}

TEST(CotanStiffness, GivesUnitMeanCurvatureOnTheUnitSphere) {
    // ΔX = −M⁻¹KX = −2Hn with H = 1 on the unit sphere (docs/formulas.md §1: exact to 1e-5 with the
    // mixed mass at level 4).
    const TriangleMesh mesh = make_icosphere(4);
    const VertexField KX = cotan_stiffness(mesh) * mesh.V;
    const Eigen::VectorXd m = lumped_masses(mesh, MassType::Voronoi);
    const Eigen::MatrixX3d N = vertex_normals(mesh);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        const double H = KX.row(i).dot(N.row(i)) / (2 * m[i]);
        ASSERT_NEAR(H, 1.0, 1e-3) << "vertex " << i;
    }
}

TEST(CotanStiffness, DegenerateFacesGiveFiniteEntries) {
    TriangleMesh mesh = make_grid(2);
    mesh.V.row(4) = 0.5 * (mesh.V.row(0) + mesh.V.row(8));  // centre onto the diagonal: flat faces
    mesh.V(4, 0) += 1e-17;
    mesh.V.conservativeResize(mesh.V.rows() + 1, 3);
    mesh.V.row(mesh.V.rows() - 1) = mesh.V.row(0);  // a duplicate point
    mesh.F.conservativeResize(mesh.F.rows() + 1, 3);
    mesh.F.row(mesh.F.rows() - 1) << 0, static_cast<int>(mesh.V.rows() - 1), 1;  // zero area
    const Eigen::MatrixXd K = cotan_stiffness(mesh);
    EXPECT_TRUE(K.allFinite());
    EXPECT_LE(K.cwiseAbs().maxCoeff(), 2 * CotanOptions{}.max_cotangent);
}

TEST(CotanStiffness, BoundedCotangentsKeepCapsPositiveSemiDefinite) {
    // A cap: angles of about 0.001°, 0.001° and 179.998°. Clamping each cotangent on its own
    // would give cot products summing to −1e6 and an indefinite K.
    TriangleMesh mesh;
    mesh.V.resize(3, 3);
    mesh.V << 0, 0, 0, 1, 0, 0, 0.5, 1e-5, 0;
    mesh.F.resize(1, 3);
    mesh.F << 0, 1, 2;
    const Eigen::MatrixXd K = cotan_stiffness(mesh);
    const Eigen::VectorXd eigenvalues =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues();
    EXPECT_GT(eigenvalues.minCoeff(), -1e-9 * eigenvalues.maxCoeff());
    EXPECT_LE(K.cwiseAbs().maxCoeff(), CotanOptions{}.max_cotangent);
}

TEST(CotanStiffness, SparsityPatternDependsOnlyOnConnectivity) {
    const TriangleMesh mesh = test::noisy_icosphere(1);
    TriangleMesh flattened = mesh;
    flattened.V.row(mesh.F(0, 2)) = 0.5 * (mesh.V.row(mesh.F(0, 0)) + mesh.V.row(mesh.F(0, 1)));
    EXPECT_EQ(cotan_stiffness(flattened).nonZeros(), cotan_stiffness(mesh).nonZeros());
}

TEST(CotanStiffness, RejectsOutOfRangeIndices) {
    TriangleMesh mesh = make_icosphere(0);
    mesh.F(3, 1) = 12;
    EXPECT_THROW((void)cotan_stiffness(mesh), InvalidInput);
    mesh.F(3, 1) = -1;
    EXPECT_THROW((void)cotan_stiffness(mesh), InvalidInput);
}

TEST(CotanStiffness, RejectsNonFinitePositions) {
    TriangleMesh mesh = make_icosphere(0);
    mesh.V(2, 2) = std::numeric_limits<double>::infinity();
    EXPECT_THROW((void)cotan_stiffness(mesh), InvalidInput);
}

}  // namespace
}  // namespace genflow
