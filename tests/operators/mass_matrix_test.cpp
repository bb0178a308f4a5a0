// SPDX-License-Identifier: MIT
#include "genflow/operators/mass_matrix.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "genflow/mesh/primitives.h"
#include "genflow/operators/area.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

TEST(MassMatrix, EveryTypeSumsToTheSurfaceArea) {
    for (const TriangleMesh& mesh :
         {test::noisy_icosphere(2, 0.2), test::noisy_torus(12, 6, 0.2), test::jittered_grid(5)}) {
        const double area = surface_area(mesh);
        for (const MassType type : {MassType::Full, MassType::Barycentric, MassType::Voronoi}) {
            EXPECT_NEAR(mass_matrix(mesh, type).sum(), area, 1e-12 * area);
            EXPECT_NEAR(lumped_masses(mesh, type).sum(), area, 1e-12 * area);
        }
    }
}

TEST(MassMatrix, LumpedTypesAreDiagonalAndPositive) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.3);
    for (const MassType type : {MassType::Barycentric, MassType::Voronoi}) {
        const Eigen::SparseMatrix<double> M = mass_matrix(mesh, type);
        EXPECT_EQ(M.nonZeros(), mesh.V.rows());
        EXPECT_GT(Eigen::VectorXd(M.diagonal()).minCoeff(), 0);
    }
}

TEST(MassMatrix, FullRowSumsAreTheBarycentricMasses) {
    const TriangleMesh mesh = test::noisy_torus(10, 6, 0.2);
    const Eigen::VectorXd row_sums =
        mass_matrix(mesh, MassType::Full) * Eigen::VectorXd::Ones(mesh.V.rows());
    EXPECT_LT((row_sums - lumped_masses(mesh, MassType::Barycentric)).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(MassMatrix, FullMatrixIntegratesProductsOfLinearFunctionsExactly) {
    // uᵀMw is the exact integral of u·w for piecewise-linear u, w; for linear u, w in the plane
    // it is a polynomial integral we know in closed form. On [0,1]²: ∫ x·y = 1/4, ∫ x² = 1/3,
    // ∫ 1·(2x − y + 1) = 1.5.
    const TriangleMesh mesh = test::jittered_grid(7);
    const Eigen::SparseMatrix<double> M = mass_matrix(mesh, MassType::Full);
    const Eigen::VectorXd x = mesh.V.col(0);
    const Eigen::VectorXd y = mesh.V.col(1);
    const Eigen::VectorXd one = Eigen::VectorXd::Ones(x.size());
    EXPECT_NEAR(x.dot(M * y), 0.25, 1e-14);
    EXPECT_NEAR(x.dot(M * x), 1.0 / 3.0, 1e-14);
    EXPECT_NEAR(one.dot(M * (2 * x - y + one)), 1.5, 1e-14);
    // The lumped matrix is exact for linear functions but not for their products.
    const Eigen::SparseMatrix<double> D = mass_matrix(mesh, MassType::Barycentric);
    EXPECT_NEAR(one.dot(D * (2 * x - y + one)), 1.5, 1e-14);
    EXPECT_GT(std::abs(x.dot(D * x) - 1.0 / 3.0), 1e-4);
}

TEST(MassMatrix, FullMatrixIsSymmetricPositiveDefinite) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.2);
    const Eigen::MatrixXd M = mass_matrix(mesh, MassType::Full);
    EXPECT_LT((M - M.transpose()).norm(), 1e-16);
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(M).info(), Eigen::Success);
}

TEST(MassMatrix, VoronoiHandlesObtuseTriangles) {
    // One obtuse triangle: A/2 at the obtuse corner, A/4 at the others.
    TriangleMesh mesh;
    mesh.V.resize(3, 3);
    mesh.V << 0, 0, 0, 4, 0, 0, 2, 0.5, 0;  // obtuse at vertex 2
    mesh.F.resize(1, 3);
    mesh.F << 0, 1, 2;
    const Eigen::VectorXd m = lumped_masses(mesh, MassType::Voronoi);
    EXPECT_NEAR(m[2], 0.5, 1e-15);
    EXPECT_NEAR(m[0], 0.25, 1e-15);
    EXPECT_NEAR(m[1], 0.25, 1e-15);
}

TEST(MassMatrix, VoronoiCellsOfARightTriangle) {
    // Right angle at vertex 0 of the unit right triangle: the Voronoi cells are 1/8 at each
    // acute corner and 1/4 at the right angle (circumcentre at the hypotenuse midpoint).
    TriangleMesh mesh;
    mesh.V.resize(3, 3);
    mesh.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
    mesh.F.resize(1, 3);
    mesh.F << 0, 1, 2;
    const Eigen::VectorXd m = lumped_masses(mesh, MassType::Voronoi);
    EXPECT_NEAR(m[0], 0.25, 1e-15);
    EXPECT_NEAR(m[1], 0.125, 1e-15);
    EXPECT_NEAR(m[2], 0.125, 1e-15);
}

TEST(MassMatrix, ZeroAreaFacesGetZeroMass) {
    TriangleMesh mesh;
    mesh.V.resize(3, 3);
    mesh.V << 0, 0, 0, 1, 0, 0, 2, 0, 0;
    mesh.F.resize(1, 3);
    mesh.F << 0, 1, 2;
    for (const MassType type : {MassType::Full, MassType::Barycentric, MassType::Voronoi}) {
        EXPECT_EQ(mass_matrix(mesh, type).norm(), 0.0);
    }
}

}  // namespace
}  // namespace genflow
