// SPDX-License-Identifier: MIT
// StiffnessPattern builds the H1 metric's matrix as Eigen's sum of sparse matrices does, to
// the bit: the flows that reuse it must not change a match's result.
#include "operators/stiffness_pattern.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <vector>

#include "genflow/energies/surface_area_energy.h"
#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mesh_size.h"
#include "metrics/metric_support.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// Same pattern and the same bits in every value (signed zeros included).
void expect_identical(const Eigen::SparseMatrix<double>& expected,
                      const Eigen::SparseMatrix<double>& actual) {
    ASSERT_EQ(actual.rows(), expected.rows());
    ASSERT_EQ(actual.nonZeros(), expected.nonZeros());
    ASSERT_TRUE(actual.isCompressed());
    const auto n = static_cast<std::size_t>(expected.nonZeros());
    EXPECT_EQ(0, std::memcmp(actual.outerIndexPtr(), expected.outerIndexPtr(),
                             sizeof(int) * static_cast<std::size_t>(expected.cols() + 1)));
    EXPECT_EQ(0, std::memcmp(actual.innerIndexPtr(), expected.innerIndexPtr(), sizeof(int) * n));
    EXPECT_EQ(0, std::memcmp(actual.valuePtr(), expected.valuePtr(), sizeof(double) * n));
}

Eigen::SparseMatrix<double> eigen_sum(const TriangleMesh& mesh, double lambda,
                                      const CotanOptions& options = {}) {
    Eigen::SparseMatrix<double> sum = detail::floored_mass_matrix(mesh, MassType::Barycentric) +
                                      lambda * cotan_stiffness(mesh, options);
    sum.makeCompressed();
    return sum;
}

// A grid with a boundary, a face collapsed to a segment, a needle (cotangents bounded), a
// vertex that no face uses, a lone face collapsed to a segment (its zero cotangents give
// entries of −0 only, which the sum must turn into +0 off the diagonal as Eigen's does), and a
// face that names one of its vertices twice (entries on that vertex's diagonal).
TriangleMesh awkward_mesh() {
    TriangleMesh mesh = test::jittered_grid(6);
    const Eigen::Index f = 7;
    mesh.V.row(mesh.F(f, 2)) = 0.5 * (mesh.V.row(mesh.F(f, 0)) + mesh.V.row(mesh.F(f, 1)));
    const Eigen::Index g = 20;
    mesh.V.row(mesh.F(g, 2)) = mesh.V.row(mesh.F(g, 0)) + 1e-7 * Eigen::RowVector3d(1, 1, 0);
    const auto n = static_cast<int>(mesh.V.rows());
    mesh.V.conservativeResize(n + 4, 3);
    mesh.V.row(n) = Eigen::RowVector3d(5, 5, 5);  // no face
    mesh.V.row(n + 1) = Eigen::RowVector3d(3, 0, 0);
    mesh.V.row(n + 2) = Eigen::RowVector3d(4, 0, 0);
    mesh.V.row(n + 3) = Eigen::RowVector3d(5, 0, 0);
    mesh.F.conservativeResize(mesh.F.rows() + 2, 3);
    mesh.F.row(mesh.F.rows() - 2) = Eigen::RowVector3i(n + 1, n + 2, n + 3);
    mesh.F.row(mesh.F.rows() - 1) = Eigen::RowVector3i(n + 3, n + 2, n + 3);
    return mesh;
}

TEST(StiffnessPattern, SumsAsEigenDoesToTheBit) {
    for (const TriangleMesh& mesh :
         {test::noisy_icosphere(3), test::noisy_torus(12, 7), awkward_mesh()}) {
        const double lambda = 3 * mean_edge_length(mesh) * mean_edge_length(mesh);
        const detail::StiffnessPattern pattern(mesh);
        const Eigen::VectorXd masses = detail::floored_lumped_masses(mesh, MassType::Barycentric);
        expect_identical(eigen_sum(mesh, lambda),
                         pattern.diagonal_plus_stiffness(mesh, masses, lambda));
        // With a bound that scales down the cotangents of most faces.
        expect_identical(
            eigen_sum(mesh, lambda, {.max_cotangent = 0.3}),
            pattern.diagonal_plus_stiffness(mesh, masses, lambda, {.max_cotangent = 0.3}));
        // Moved vertices, the same faces: the pattern is reused.
        TriangleMesh moved = mesh;
        moved.V = 1.7 * mesh.V + 0.1 * mesh.V.cwiseAbs2();
        ASSERT_TRUE(pattern.fits(moved));
        expect_identical(
            eigen_sum(moved, lambda),
            pattern.diagonal_plus_stiffness(
                moved, detail::floored_lumped_masses(moved, MassType::Barycentric), lambda));
    }
}

TEST(StiffnessPattern, FitsItsConnectivityOnly) {
    const TriangleMesh mesh = test::noisy_icosphere(2);
    const detail::StiffnessPattern pattern(mesh);
    EXPECT_TRUE(pattern.fits(mesh));
    TriangleMesh flipped = mesh;
    flipped.F.row(3) = mesh.F.row(3).reverse();
    EXPECT_FALSE(pattern.fits(flipped));
    TriangleMesh extra = mesh;
    extra.V.conservativeResize(mesh.V.rows() + 1, 3);
    extra.V.row(mesh.V.rows()).setZero();
    EXPECT_FALSE(pattern.fits(extra));
    EXPECT_THROW(
        (void)pattern.diagonal_plus_stiffness(flipped, Eigen::VectorXd::Ones(mesh.V.rows()), 1.0),
        InvalidInput);
    EXPECT_THROW((void)pattern.diagonal_plus_stiffness(mesh, Eigen::VectorXd::Ones(3), 1.0),
                 InvalidInput);
}

// The H1 metric keeps one pattern and builds another when the faces change.
TEST(StiffnessPattern, H1MetricFollowsAChangeOfConnectivity) {
    const TriangleMesh sphere = test::noisy_icosphere(2);
    const TriangleMesh torus = test::noisy_torus(10, 6);
    const double lambda = 0.01;
    H1Metric metric({.lambda = lambda});
    for (const TriangleMesh* mesh : {&sphere, &torus, &sphere}) {
        metric.update(*mesh);
        expect_identical(eigen_sum(*mesh, lambda), metric.matrix());
    }
}

// The largest entry of |A − K| for the area's linearization A at `mesh` and its stiffness K
// (the cotangents bounded by 2, as `area` is made).
double distance_to_stiffness(const SurfaceAreaEnergy& area, const TriangleMesh& mesh) {
    const auto linearization = area.linearize(mesh);
    if (!linearization) {
        ADD_FAILURE() << "the area has no linearization";
        return std::numeric_limits<double>::infinity();
    }
    EXPECT_EQ(linearization->B.cwiseAbs().maxCoeff(), 0.0);
    const Eigen::SparseMatrix<double> K = cotan_stiffness(mesh, {.max_cotangent = 2.0});
    return Eigen::MatrixXd(linearization->A - K).cwiseAbs().maxCoeff();
}

// The area's linearization K comes from a pattern cache: the values of cotan_stiffness() at
// every step of a flow, after a change of connectivity, and in a copy.
TEST(StiffnessPattern, AreaLinearizationIsTheStiffnessMatrix) {
    const TriangleMesh sphere = test::noisy_icosphere(2);
    const TriangleMesh torus = test::noisy_torus(10, 6);
    const TriangleMesh moved{1.3 * sphere.V + 0.2 * sphere.V.cwiseAbs2(), sphere.F};
    const TriangleMesh awkward = awkward_mesh();
    const SurfaceAreaEnergy area({.max_cotangent = 2.0});
    for (const TriangleMesh* mesh : {&sphere, &moved, &torus, &sphere, &awkward}) {
        EXPECT_EQ(distance_to_stiffness(area, *mesh), 0.0);
    }
    // A copy keeps its own cache: each follows its own mesh.
    const SurfaceAreaEnergy copy = area;
    for (int round = 0; round < 2; ++round) {
        EXPECT_EQ(distance_to_stiffness(copy, torus), 0.0);
        EXPECT_EQ(distance_to_stiffness(area, sphere), 0.0);
    }
}

}  // namespace
}  // namespace genflow
