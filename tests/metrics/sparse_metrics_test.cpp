// SPDX-License-Identifier: MIT
// Every sparse metric: G symmetric positive definite, gradient inverts apply, a gradient step
// decreases the energy, fixed vertices stay put, the symbolic analysis is reused.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <functional>
#include <memory>

#include "genflow/energies/surface_area_energy.h"
#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/metrics/l2_metric.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mesh_size.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

struct MetricCase {
    const char* name;
    std::function<std::unique_ptr<SparseMetric>(double h)> make;
};

class SparseMetrics : public ::testing::TestWithParam<MetricCase> {};

TEST_P(SparseMetrics, AreSymmetricPositiveDefinite) {
    for (const TriangleMesh& mesh : {test::noisy_icosphere(2), test::jittered_grid(5)}) {
        auto metric = GetParam().make(mean_edge_length(mesh));
        metric->update(mesh);
        const Eigen::MatrixXd G = metric->matrix();
        EXPECT_LT((G - G.transpose()).norm(), 1e-14 * G.norm());
        const Eigen::VectorXd eigenvalues =
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(G).eigenvalues();
        EXPECT_GT(eigenvalues.minCoeff(), 1e-8 * eigenvalues.maxCoeff());
    }
}

TEST_P(SparseMetrics, GradientInvertsApply) {
    const TriangleMesh mesh = test::noisy_torus(14, 7);
    auto metric = GetParam().make(mean_edge_length(mesh));
    metric->update(mesh);
    const VertexField U = test::noisy_torus(14, 7, 0.3, 9).V;  // any field
    EXPECT_LT(test::relative_error(metric->gradient(metric->apply(U)), U), 1e-10);
    EXPECT_LT(test::relative_error(metric->apply(metric->gradient(U)), U), 1e-10);
}

TEST_P(SparseMetrics, GradientStepDecreasesTheArea) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.3);
    auto metric = GetParam().make(mean_edge_length(mesh));
    metric->update(mesh);
    const SurfaceAreaEnergy area;
    const VertexField dEdX = area.differential(mesh);
    const VertexField g = metric->gradient(dEdX);
    EXPECT_GT((dEdX.array() * g.array()).sum(), 0);  // ‖g‖²_G > 0: a descent direction
    TriangleMesh moved = mesh;
    moved.V -= 1e-3 * g / g.norm() * mesh.V.norm();
    EXPECT_LT(area.value(moved), area.value(mesh));
}

TEST_P(SparseMetrics, FixedVerticesDoNotMove) {
    const TriangleMesh mesh = test::jittered_grid(6);
    auto metric = GetParam().make(mean_edge_length(mesh));
    std::vector<bool> fixed(static_cast<std::size_t>(mesh.V.rows()), false);
    fixed[0] = fixed[10] = fixed[24] = true;
    metric->set_fixed_vertices(fixed);
    metric->update(mesh);
    const VertexField dEdX = test::random_matrix(mesh.V.rows(), 3, 1);
    const VertexField g = metric->gradient(dEdX);
    const VertexField s = metric->shifted_gradient(cotan_stiffness(mesh), 0.3, dEdX);
    for (const int i : {0, 10, 24}) {
        EXPECT_EQ(g.row(i).norm(), 0.0);
        EXPECT_EQ(s.row(i).norm(), 0.0);
    }
    EXPECT_GT(g.norm(), 0.0);
    metric->set_fixed_vertices(std::vector<bool>(3, true));
    EXPECT_THROW(metric->update(mesh), InvalidInput);
}

TEST_P(SparseMetrics, ReuseTheSymbolicAnalysisWhileThePatternStays) {
    TriangleMesh mesh = test::noisy_icosphere(2);
    auto metric = GetParam().make(mean_edge_length(mesh));
    const Eigen::SparseMatrix<double> K = cotan_stiffness(mesh);
    for (int step = 0; step < 3; ++step) {
        metric->update(mesh);
        (void)metric->shifted_gradient(K, 0.1, mesh.V);
        mesh.V *= 1.01;
    }
    EXPECT_EQ(metric->symbolic_analyses(), 2);  // once for G, once for G + dt·A
}

// update_alongside() runs its task once and factors as update() does, to the bit.
TEST_P(SparseMetrics, UpdateAlongsideRunsTheTaskAndFactorsAsUpdateDoes) {
    const TriangleMesh mesh = test::noisy_icosphere(3);
    auto metric = GetParam().make(mean_edge_length(mesh));
    const VertexField differential = SurfaceAreaEnergy{}.differential(mesh);
    metric->update(mesh);
    const VertexField gradient = metric->gradient(differential);
    int runs = 0;
    metric->update_alongside(mesh, [&runs] { ++runs; });
    EXPECT_EQ(runs, 1);
    EXPECT_EQ(metric->gradient(differential), gradient);
    EXPECT_THROW(metric->update_alongside(mesh, [] { throw InvalidInput("task"); }), InvalidInput);
    metric->update_alongside(mesh, {});  // no task
    EXPECT_EQ(metric->gradient(differential), gradient);
}

TEST_P(SparseMetrics, RefuseUseBeforeUpdateAndWrongSizes) {
    auto metric = GetParam().make(0.1);
    EXPECT_THROW((void)metric->gradient(VertexField::Zero(3, 3)), InvalidInput);
    const TriangleMesh mesh = make_icosphere(1);
    metric->update(mesh);
    EXPECT_THROW((void)metric->gradient(VertexField::Zero(3, 3)), InvalidInput);
    EXPECT_THROW((void)metric->update(TriangleMesh{}), InvalidInput);
}

INSTANTIATE_TEST_SUITE_P(
    Metrics, SparseMetrics,
    ::testing::Values(
        MetricCase{"L2Barycentric", [](double) { return std::make_unique<L2Metric>(); }},
        MetricCase{"L2Voronoi",
                   [](double) {
                       return std::make_unique<L2Metric>(L2Options{.mass = MassType::Voronoi});
                   }},
        MetricCase{
            "L2Full",
            [](double) { return std::make_unique<L2Metric>(L2Options{.mass = MassType::Full}); }},
        MetricCase{"H1",
                   [](double h) {
                       return std::make_unique<H1Metric>(SobolevOptions{.lambda = 4 * h * h});
                   }},
        MetricCase{"H1InHalves",
                   [](double h) {
                       return std::make_unique<H1Metric>(SobolevOptions{
                           .lambda = 4 * h * h, .factorization = Factorization::ByFlopDensityWide});
                   }},
        MetricCase{"H1Full",
                   [](double h) {
                       return std::make_unique<H1Metric>(
                           SobolevOptions{.lambda = h * h, .mass = MassType::Full});
                   }},
        MetricCase{"H2",
                   [](double h) {
                       return std::make_unique<H2Metric>(
                           SobolevOptions{.lambda = h * h, .mu = h * h * h * h});
                   }}),
    [](const ::testing::TestParamInfo<MetricCase>& param_info) {
        return std::string(param_info.param.name);
    });

TEST(SobolevMetrics, RejectBadParameters) {
    EXPECT_THROW(H1Metric({.lambda = 0}), InvalidInput);
    EXPECT_THROW(H1Metric({.lambda = INFINITY}), InvalidInput);
    EXPECT_THROW(H2Metric({.lambda = 1, .mu = -1}), InvalidInput);
}

TEST(SobolevMetrics, H2WithZeroMuIsH1) {
    const TriangleMesh mesh = test::noisy_icosphere(2);
    H1Metric h1({.lambda = 0.01});
    H2Metric h2({.lambda = 0.01, .mu = 0});
    h1.update(mesh);
    h2.update(mesh);
    EXPECT_LT(test::relative_error(Eigen::MatrixXd(h2.matrix()), Eigen::MatrixXd(h1.matrix())),
              1e-15);
}

TEST(L2Metric, IsolatedVerticesDoNotBreakTheFactorization) {
    TriangleMesh mesh = make_icosphere(1);
    mesh.V.conservativeResize(mesh.V.rows() + 1, 3);
    mesh.V.row(mesh.V.rows() - 1) << 5, 5, 5;  // unreferenced: zero mass
    L2Metric metric;
    metric.update(mesh);
    const VertexField g = metric.gradient(SurfaceAreaEnergy{}.differential(mesh));
    EXPECT_TRUE(g.allFinite());
    EXPECT_EQ(g.row(mesh.V.rows() - 1).norm(), 0.0);
}

}  // namespace
}  // namespace genflow
