// SPDX-License-Identifier: MIT
#include "genflow/energies/pseudo_hausdorff_energy.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "genflow/exceptions.h"
#include "genflow/flows/implicit_euler.h"
#include "genflow/io/read_mesh.h"
#include "genflow/mesh/primitives.h"
#include "genflow/metrics/l2_metric.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"
#include "support/reference_distances.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

struct Pair {
    TriangleMesh X;
    TriangleMesh Y;
};

// A small irregular source and a differently sampled, shifted and stretched target.
Pair small_pair() {
    TriangleMesh Y = test::noisy_icosphere(2, 0.15, 7);
    Y.V = Y.V * Eigen::Vector3d(1.1, 1.0, 0.95).asDiagonal();
    Y.V.rowwise() += Eigen::RowVector3d(0.15, 0.0, -0.05);
    return {test::noisy_icosphere(1, 0.2, 3), Y};
}

PseudoHausdorffEvaluation evaluate(const Pair& pair, const PseudoHausdorffOptions& options) {
    return pseudo_hausdorff(pair.X.V, lumped_masses(pair.X, MassType::Barycentric), pair.Y.V,
                            lumped_masses(pair.Y, MassType::Barycentric), options);
}

// Brute-force Hausdorff distance between the vertex sets.
using test::vertex_hausdorff;

TEST(PseudoHausdorff, DifferentialMatchesFiniteDifferencesForSeveralAlphaAndEpsilon) {
    const Pair pair = small_pair();
    const Eigen::VectorXd mx = lumped_masses(pair.X, MassType::Barycentric);
    const Eigen::VectorXd my = lumped_masses(pair.Y, MassType::Barycentric);
    for (const auto& [alpha, epsilon] :
         {std::pair{1.0, 0.05}, {4.0, 0.05}, {10.0, 0.02}, {20.0, 0.01}, {7.5, 0.03}}) {
        for (const double truncation : {0.0, 1e-12}) {
            const PseudoHausdorffOptions options{
                .alpha = alpha, .epsilon = epsilon, .truncation = truncation};
            const auto value = [&](const TriangleMesh& m) {
                return pseudo_hausdorff(m.V, mx, pair.Y.V, my, options).value;
            };
            const VertexField fd = test::finite_difference_gradient(value, pair.X, 1e-6);
            const VertexField analytic =
                pseudo_hausdorff(pair.X.V, mx, pair.Y.V, my, options).differential;
            EXPECT_LT(test::relative_error(analytic, fd), 1e-6)
                << "alpha " << alpha << " truncation " << truncation;
        }
    }
}

TEST(PseudoHausdorff, TruncationStaysWithinItsBound) {
    const Pair pair = small_pair();
    for (const double alpha : {8.0, 16.0}) {
        const auto exact = evaluate(pair, {.alpha = alpha, .epsilon = 0.02, .truncation = 0});
        for (const double tau : {1e-2, 1e-4, 1e-8}) {
            const auto truncated =
                evaluate(pair, {.alpha = alpha, .epsilon = 0.02, .truncation = tau});
            const double bound = tau / (2 * alpha * (1 - tau));
            EXPECT_LE(std::abs(truncated.value - exact.value) / (exact.value + 0.02), bound) << tau;
            EXPECT_LT(test::relative_error(truncated.differential, exact.differential), 100 * tau)
                << tau;
            EXPECT_LT(truncated.pairs, exact.pairs);
        }
    }
}

TEST(PseudoHausdorff, RepeatsTheNeighbourQueriesBeyondTheStorageBudget) {
    const Pair pair = small_pair();
    const auto stored = evaluate(pair, {.alpha = 8, .epsilon = 0.02, .truncation = 1e-4});
    const auto requeried =
        evaluate(pair, {.alpha = 8, .epsilon = 0.02, .truncation = 1e-4, .stored_term_budget = 50});
    EXPECT_EQ(requeried.value, stored.value);
    EXPECT_LT(test::relative_error(requeried.differential, stored.differential), 1e-13);
}

TEST(PseudoHausdorff, IsSymmetric) {
    const Pair pair = small_pair();
    const Eigen::VectorXd mx = lumped_masses(pair.X, MassType::Barycentric);
    const Eigen::VectorXd my = lumped_masses(pair.Y, MassType::Barycentric);
    const PseudoHausdorffOptions options{.alpha = 8, .epsilon = 0.01, .truncation = 0};
    EXPECT_NEAR(pseudo_hausdorff(pair.X.V, mx, pair.Y.V, my, options).value,
                pseudo_hausdorff(pair.Y.V, my, pair.X.V, mx, options).value, 1e-13);
}

TEST(PseudoHausdorff, OfIdenticalMeshesIsWithinTheEpsilonOffset) {
    const TriangleMesh mesh = test::noisy_icosphere(3, 0.1);
    const double epsilon = 0.1 * mean_edge_length(mesh);
    for (const double alpha : {4.0, 8.0, 16.0}) {
        const PseudoHausdorffEnergy energy(mesh, {.alpha = alpha, .epsilon = epsilon});
        const double value = energy.value(mesh);
        // f_i ≥ b_i ε^{−2α} gives S ≤ 2P ε^{2α}: d_H ≤ ε((2P)^{1/(2α)} − 1); and d_H > −ε.
        const double P = static_cast<double>(mesh.V.rows());
        EXPECT_LE(value, epsilon * (std::pow(2 * P, 1 / (2 * alpha)) - 1) * (1 + 1e-9)) << alpha;
        EXPECT_GT(value, -epsilon);
    }
}

TEST(PseudoHausdorff, ApproachesTheVertexHausdorffDistanceAsAlphaGrows) {
    // Two different shapes, and two samplings of the same shape (SPEC.md §8: the limit is the
    // ε-regularized Hausdorff distance between the vertex sets, not between the surfaces).
    const TriangleMesh sphere = make_icosphere(3);
    TriangleMesh resampled = make_icosphere(2);
    resampled.V = resampled.V *
                  Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    TriangleMesh ellipsoid = resampled;
    ellipsoid.V = ellipsoid.V * Eigen::Vector3d(1.2, 1.0, 0.9).asDiagonal();
    const double epsilon = 1e-3;
    for (const TriangleMesh* target : {&resampled, &ellipsoid}) {
        const double hausdorff = vertex_hausdorff(sphere.V, target->V);
        const double limit = std::sqrt(hausdorff * hausdorff + epsilon * epsilon) - epsilon;
        // Not monotone in α (SPEC.md §8's table), but the soft-min bias of small α disappears.
        const auto error = [&](double alpha) {
            const PseudoHausdorffEnergy energy(*target, {.alpha = alpha, .epsilon = epsilon});
            return std::abs(energy.value(sphere) - limit) / limit;
        };
        const double at_1024 = error(1024);
        EXPECT_LT(at_1024, 0.005);
        EXPECT_LT(at_1024, error(2));
        EXPECT_LT(error(256), 0.02);
    }
}

TEST(PseudoHausdorff, IsScaleEquivariantAndStableFromMicroToKilo) {
    const Pair pair = small_pair();
    const auto base = evaluate(pair, {.alpha = 20, .epsilon = 0.01, .truncation = 0});
    for (const double scale : {1e-3, 1e3}) {
        Pair scaled = pair;
        scaled.X.V *= scale;
        scaled.Y.V *= scale;
        for (const double truncation : {0.0, 1e-4}) {
            const auto result =
                evaluate(scaled, {.alpha = 20, .epsilon = 0.01 * scale, .truncation = truncation});
            EXPECT_NEAR(result.value / scale, base.value, 1e-4 * base.value) << scale;
            EXPECT_TRUE(result.differential.allFinite());
            EXPECT_LT(test::relative_error(result.differential, base.differential), 1e-3) << scale;
        }
    }
}

TEST(PseudoHausdorff, NearlyCoincidentMeshesAtHighAlphaStayFinite) {
    const TriangleMesh X = make_icosphere(2);
    const TriangleMesh Y = add_noise(X, 1e-5, 9);
    for (const double alpha : {20.0, 50.0, 150.0}) {
        const PseudoHausdorffEnergy energy(Y, {.alpha = alpha, .epsilon = 1e-4, .truncation = 0});
        const auto result = energy.evaluate(X);
        EXPECT_TRUE(std::isfinite(result.value));
        EXPECT_GT(result.value, 0);  // the naive float64 formula returns −ε here
        EXPECT_TRUE(result.differential.allFinite());
    }
}

TEST(PseudoHausdorff, LinearizationReproducesTheDifferential) {
    const Pair pair = small_pair();
    const PseudoHausdorffEnergy energy(pair.Y, {.alpha = 8, .epsilon = 0.02});
    const auto linearization = energy.linearize(pair.X);
    ASSERT_TRUE(linearization);
    EXPECT_LT(test::relative_error(linearization->A * pair.X.V + linearization->B,
                                   energy.differential(pair.X)),
              1e-12);
    EXPECT_GT(Eigen::VectorXd(linearization->A.diagonal()).minCoeff(), 0);
}

TEST(PseudoHausdorff, AnImplicitL2FlowDecreasesIt) {
    const Pair pair = small_pair();
    const PseudoHausdorffEnergy energy(pair.Y, {.alpha = 8, .epsilon = 0.05});
    L2Metric metric;
    const FlowResult result =
        implicit_euler(pair.X, energy, metric, {.time_step = 0.1, .max_steps = 20});
    ASSERT_TRUE(result.ok()) << result.message;
    for (std::size_t k = 1; k < result.energy.size(); ++k) {
        EXPECT_LT(result.energy[k], result.energy[k - 1]) << k;
    }
    EXPECT_LT(result.energy.back(), 0.7 * result.energy.front());
}

TEST(PseudoHausdorff, TruncatedAgreesWithFullSumsOnARealPair) {
    const auto data = test::data_directory();
    if (!data) {
        GTEST_SKIP() << "no data directory (set GENFLOW_DATA)";
    }
    // The end of a matching: the same surface in two samplings (ground truth vs remeshed).
    const TriangleMesh X = read_mesh(*data / "matching/small/tosca_cat_0_4_small_target.ply");
    const TriangleMesh Y =
        read_mesh(*data / "matching/small/tosca_cat_0_4_small_target_remeshed.ply");
    const double epsilon = mean_edge_length(Y);
    const PseudoHausdorffEnergy exact(Y, {.alpha = 8, .epsilon = epsilon, .truncation = 0});
    const PseudoHausdorffEnergy truncated(Y, {.alpha = 8, .epsilon = epsilon, .truncation = 1e-4});
    const auto e = exact.evaluate(X);
    const auto t = truncated.evaluate(X);
    EXPECT_LE(std::abs(t.value - e.value) / (e.value + epsilon), 1e-4 / (16 * (1 - 1e-4)));
    EXPECT_LT(test::relative_error(t.differential, e.differential), 1e-3);
    EXPECT_LT(static_cast<double>(t.pairs), 0.2 * static_cast<double>(e.pairs));
}

TEST(PseudoHausdorff, RejectsBadInput) {
    const TriangleMesh mesh = make_icosphere(1);
    EXPECT_THROW(PseudoHausdorffEnergy(mesh, {.alpha = 8, .epsilon = 0}), InvalidInput);
    EXPECT_THROW(PseudoHausdorffEnergy(mesh, {.alpha = 0.1, .epsilon = 1}), InvalidInput);
    EXPECT_THROW(PseudoHausdorffEnergy(mesh, {.alpha = 8, .epsilon = 1, .truncation = 0.7}),
                 InvalidInput);
    EXPECT_THROW(PseudoHausdorffEnergy(TriangleMesh{}, {.alpha = 8, .epsilon = 1}), InvalidInput);
    const PseudoHausdorffEnergy energy(mesh, {.alpha = 8, .epsilon = 0.1});
    TriangleMesh bad = mesh;
    bad.V(0, 0) = NAN;
    EXPECT_THROW((void)energy.value(bad), InvalidInput);
    EXPECT_THROW(
        (void)pseudo_hausdorff(mesh.V, Eigen::VectorXd::Ones(3), mesh.V,
                               Eigen::VectorXd::Ones(mesh.V.rows()), {.alpha = 8, .epsilon = 0.1}),
        InvalidInput);
}

}  // namespace
}  // namespace genflow
