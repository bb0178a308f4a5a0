// SPDX-License-Identifier: MIT
// The quasi-isometric metric (docs/formulas.md §7): G equals the edge-sum inner product, is SPD,
// costs rigid motions only their L2 norm, means the same at every resolution, inverts exactly, and
// solves the implicit step; fake edges join opposite sides of a limb.
#include "genflow/metrics/quasi_isometric_metric.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <map>
#include <random>
#include <set>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/area.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

VertexField random_field(Eigen::Index n, unsigned seed) {
    std::mt19937 generator(seed);
    std::normal_distribution<double> normal;
    VertexField field(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) {
            field(i, c) = normal(generator);
        }
    }
    return field;
}

// ⟨U, V⟩ of docs/formulas.md §7 summed edge by edge, with A_e from an edge → faces map: independent
// of the metric's per-face assembly.
double edge_sum_inner_product(const TriangleMesh& mesh, double lambda, const VertexField& U,
                              const VertexField& V) {
    const Eigen::VectorXd m = lumped_masses(mesh, MassType::Barycentric);
    double product = (U.array() * V.array()).rowwise().sum().matrix().dot(m);
    const Eigen::VectorXd areas = face_areas(mesh);
    std::map<std::pair<int, int>, double> edge_area;
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            const int a = mesh.F(f, k);
            const int b = mesh.F(f, (k + 1) % 3);
            edge_area[{std::min(a, b), std::max(a, b)}] += areas[f] / 3;
        }
    }
    for (const auto& [edge, area] : edge_area) {
        const auto [i, j] = edge;
        const Eigen::RowVector3d d = mesh.V.row(i) - mesh.V.row(j);
        const double w = area / std::pow(d.squaredNorm(), 2);
        product += lambda * w * (U.row(i) - U.row(j)).dot(d) * (V.row(i) - V.row(j)).dot(d);
    }
    return product;
}

double lambda_of(const TriangleMesh& mesh, const QuasiIsometricOptions& options) {
    return std::pow(options.rigidity_length * bounding_box_diagonal(mesh), 2);
}

TEST(QuasiIsometricMetric, EqualsTheEdgeSumInnerProduct) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.15);
    const QuasiIsometricOptions options{.rigidity_length = 0.3};
    QuasiIsometricMetric metric(options);
    metric.update(mesh);
    const VertexField U = random_field(mesh.V.rows(), 1);
    const VertexField V = random_field(mesh.V.rows(), 2);
    const double expected = edge_sum_inner_product(mesh, lambda_of(mesh, options), U, V);
    EXPECT_NEAR((U.array() * metric.apply(V).array()).sum(), expected, 1e-11 * std::abs(expected));
    EXPECT_NEAR((V.array() * metric.apply(U).array()).sum(), expected, 1e-11 * std::abs(expected));
}

TEST(QuasiIsometricMetric, IsSymmetricPositiveDefinite) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.15);
    QuasiIsometricMetric metric({.rigidity_length = 0.5, .fake_edges = 6});
    metric.update(mesh);
    const Eigen::MatrixXd G = metric.matrix();
    EXPECT_LE((G - G.transpose()).norm(), 1e-14 * G.norm());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(G);
    EXPECT_GT(eigen.eigenvalues().minCoeff(), 0.0);
    EXPECT_FALSE(metric.fake_edges().empty());
}

TEST(QuasiIsometricMetric, RigidMotionsCostOnlyTheirL2Norm) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.15);
    QuasiIsometricMetric metric({.rigidity_length = 0.5, .fake_edges = 10});
    metric.update(mesh);
    const Eigen::VectorXd m = lumped_masses(mesh, MassType::Barycentric);
    const Eigen::Vector3d omega(0.3, -1.2, 0.7);
    const Eigen::Vector3d centre(0.4, 0.1, -2);
    VertexField rigid(mesh.V.rows(), 3);
    VertexField stretch(mesh.V.rows(), 3);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        const Eigen::Vector3d x = mesh.V.row(i).transpose();
        rigid.row(i) = (omega.cross(x - centre) + Eigen::Vector3d(1, 2, 3)).transpose();
        stretch.row(i) << x[0], 0, 0;
    }
    const VertexField mass_times_rigid = rigid.array().colwise() * m.array();
    EXPECT_LT((metric.apply(rigid) - mass_times_rigid).norm(), 1e-12 * mass_times_rigid.norm());
    const VertexField mass_times_stretch = stretch.array().colwise() * m.array();
    EXPECT_GT((metric.apply(stretch) - mass_times_stretch).norm(), 0.1 * mass_times_stretch.norm());
}

// docs/formulas.md §7: with w_e = A_e/|d_e|⁴ the stretch field (x, 0, 0) on the unit sphere costs
// the same relative to its L2 norm at every resolution (0.6 λ), where w_e = 1 falls as h².
TEST(QuasiIsometricMetric, MeansTheSameAtEveryResolution) {
    std::vector<double> ratios;
    for (const int level : {2, 3, 4}) {
        const TriangleMesh sphere = make_icosphere(level);
        const QuasiIsometricOptions options{.rigidity_length = 0.5};
        QuasiIsometricMetric metric(options);
        metric.update(sphere);
        VertexField stretch = VertexField::Zero(sphere.V.rows(), 3);
        stretch.col(0) = sphere.V.col(0);
        const Eigen::VectorXd m = lumped_masses(sphere, MassType::Barycentric);
        const double l2 = stretch.col(0).cwiseAbs2().dot(m);
        const double total = (stretch.array() * metric.apply(stretch).array()).sum();
        ratios.push_back((total - l2) / lambda_of(sphere, options) / l2);
    }
    for (const double ratio : ratios) {
        EXPECT_NEAR(ratio, 0.6, 0.01);
    }
}

TEST(QuasiIsometricMetric, GradientInvertsApplyAndKeepsFixedVerticesStill) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.15);
    QuasiIsometricMetric metric({.rigidity_length = 0.2});
    metric.update(mesh);
    const VertexField U = random_field(mesh.V.rows(), 3);
    EXPECT_LT((metric.gradient(metric.apply(U)) - U).norm(), 1e-10 * U.norm());

    std::vector<bool> fixed(static_cast<std::size_t>(mesh.V.rows()), false);
    fixed[0] = fixed[7] = true;
    metric.set_fixed_vertices(fixed);
    metric.update(mesh);
    const VertexField g = metric.gradient(random_field(mesh.V.rows(), 4));
    EXPECT_EQ(g.row(0).norm(), 0.0);
    EXPECT_EQ(g.row(7).norm(), 0.0);
    EXPECT_GT(g.row(1).norm(), 0.0);
}

// With refresh_interval k, G is that of the last rebuild for k − 1 updates, then follows the mesh.
TEST(QuasiIsometricMetric, RebuildsEveryRefreshInterval) {
    TriangleMesh mesh = test::noisy_icosphere(1, 0.15);
    QuasiIsometricMetric lagged({.rigidity_length = 0.3, .refresh_interval = 3});
    QuasiIsometricMetric exact({.rigidity_length = 0.3});
    lagged.update(mesh);
    const Eigen::SparseMatrix<double> first = lagged.matrix();
    for (int update = 1; update <= 3; ++update) {
        mesh.V *= 1.1;
        lagged.update(mesh);
        exact.update(mesh);
        const double lag = (Eigen::MatrixXd(lagged.matrix()) - Eigen::MatrixXd(first)).norm();
        const double gap =
            (Eigen::MatrixXd(lagged.matrix()) - Eigen::MatrixXd(exact.matrix())).norm();
        if (update < 3) {
            EXPECT_EQ(lag, 0.0) << update;
            EXPECT_GT(gap, 0.0) << update;
        } else {
            EXPECT_EQ(gap, 0.0);
        }
    }
    const VertexField U = random_field(mesh.V.rows(), 8);
    EXPECT_LT((lagged.gradient(lagged.apply(U)) - U).norm(), 1e-10 * U.norm());
}

TEST(QuasiIsometricMetric, ImplicitStepSolvesTheShiftedSystem) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.15);
    QuasiIsometricMetric metric({.rigidity_length = 0.3});
    metric.update(mesh);
    const Eigen::Index n = mesh.V.rows();
    Eigen::SparseMatrix<double> A(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
        A.insert(i, i) = 0.5 + static_cast<double>(i % 3);
    }
    const double dt = 0.7;
    const VertexField R = random_field(n, 5);
    const VertexField X = metric.shifted_gradient(A, dt, R);
    // (G + dt·A⊗I₃) X = R, checked through apply().
    const VertexField residual = metric.apply(X) + dt * (A * X) - R;
    EXPECT_LT(residual.norm(), 1e-10 * R.norm());
}

// On a long thin ellipsoid, the rays from the sides cross the limb: a fake edge is about as
// long as the limb is thick, far shorter than the limb. Only the rays from the two tips (the
// first two samples) run along it.
TEST(QuasiIsometricMetric, FakeEdgesCrossTheLimb) {
    const TriangleMesh limb = make_ellipsoid(3, Eigen::Vector3d(3, 0.4, 0.4));
    const auto pairs = cross_limb_pairs(limb, 30);
    ASSERT_GE(pairs.size(), 20U);
    std::set<std::pair<int, int>> distinct(pairs.begin(), pairs.end());
    EXPECT_EQ(distinct.size(), pairs.size());
    int across = 0;
    for (const auto& [i, j] : pairs) {
        EXPECT_NE(i, j);
        const double length = (limb.V.row(i) - limb.V.row(j)).norm();
        EXPECT_GT(length, 0.3) << i << " " << j;  // across, not a neighbour
        across += length < 1.0 ? 1 : 0;           // thickness 0.8, length 6
    }
    EXPECT_GE(across, static_cast<int>(pairs.size()) - 2);
}

TEST(QuasiIsometricMetric, RefusesBadOptionsAndMisuse) {
    const TriangleMesh mesh = make_icosphere(1);
    QuasiIsometricMetric negative({.rigidity_length = -1});
    EXPECT_THROW(negative.update(mesh), InvalidInput);
    QuasiIsometricMetric not_finite({.rigidity_length = std::nan("")});
    EXPECT_THROW(not_finite.update(mesh), InvalidInput);
    QuasiIsometricMetric never({.refresh_interval = 0});
    EXPECT_THROW(never.update(mesh), InvalidInput);
    QuasiIsometricMetric metric;
    EXPECT_THROW((void)metric.gradient(VertexField::Zero(mesh.V.rows(), 3)), InvalidInput);
    metric.update(mesh);
    EXPECT_THROW((void)metric.apply(VertexField::Zero(3, 3)), InvalidInput);
    metric.set_fixed_vertices({true});
    EXPECT_THROW(metric.update(mesh), InvalidInput);
}

}  // namespace
}  // namespace genflow
