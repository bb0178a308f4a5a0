// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>

#include "genflow/energies/enclosed_volume_energy.h"
#include "genflow/energies/surface_area_energy.h"
#include "genflow/exceptions.h"
#include "genflow/flows/explicit_euler.h"
#include "genflow/flows/implicit_euler.h"
#include "genflow/mesh/primitives.h"
#include "genflow/metrics/l2_metric.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// (M + dt K) X' = M X, solved directly.
Eigen::MatrixX3d implicit_fairing_step(const TriangleMesh& mesh, MassType mass, double dt) {
    const Eigen::SparseMatrix<double> M = mass_matrix(mesh, mass);
    const Eigen::SparseMatrix<double> system = M + dt * cotan_stiffness(mesh);
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> solver(system);
    return solver.solve(Eigen::MatrixXd(M * mesh.V));
}

// The identity of paper §4 (docs/formulas.md §2): one explicit H1 step of the area with λ = dt is
// one implicit-fairing step, and so is one implicit (eq. 11) L2 step.
TEST(Integrators, ExplicitH1StepOfAreaIsImplicitFairing) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.2);
    for (const MassType mass : {MassType::Barycentric, MassType::Full}) {
        for (const double dt : {1e-3, 0.1, 10.0}) {
            const Eigen::MatrixX3d expected = implicit_fairing_step(mesh, mass, dt);
            const FlowOptions options{.time_step = dt, .max_steps = 1};
            H1Metric h1({.lambda = dt, .mass = mass});
            const FlowResult explicit_h1 = explicit_euler(mesh, SurfaceAreaEnergy{}, h1, options);
            EXPECT_LT(test::relative_error(explicit_h1.mesh.V, expected), 1e-10) << "dt " << dt;
            L2Metric l2({.mass = mass});
            const FlowResult implicit_l2 = implicit_euler(mesh, SurfaceAreaEnergy{}, l2, options);
            EXPECT_LT(test::relative_error(implicit_l2.mesh.V, expected), 1e-10) << "dt " << dt;
        }
    }
}

// An explicit step takes dE/dX computed while the metric updates to the same mesh (alongside
// the factorization in two halves): the same bits as a step that computes it after.
TEST(Integrators, ExplicitStepsAreThoseOfTheDifferentialAtEachStepsMesh) {
    const TriangleMesh mesh = test::noisy_icosphere(5, 0.2);  // 10,242 vertices: in two halves
    const double dt = 0.5 * mean_edge_length(mesh) * mean_edge_length(mesh);
    const SobolevOptions metric_options{.lambda = dt,
                                        .factorization = Factorization::ByFlopDensityWide};
    H1Metric flowing(metric_options);
    const FlowResult flow = explicit_euler(mesh, SurfaceAreaEnergy{}, flowing,
                                           FlowOptions{.time_step = dt, .max_steps = 3});
    H1Metric stepping(metric_options);
    Eigen::MatrixX3d V = mesh.V;
    for (int step = 0; step < 3; ++step) {
        const TriangleMesh current{V, mesh.F};
        stepping.update(current);
        V += -dt * stepping.gradient(SurfaceAreaEnergy{}.differential(current));
    }
    ASSERT_EQ(flow.steps, 3);
    EXPECT_EQ(flow.mesh.V, V);
}

TEST(Integrators, MeanCurvatureFlowShrinksASphereAsR2Minus4t) {
    // dX/dt = ΔX = −2H n with H = 1/r: r(t)² = r0² − 4t.
    const TriangleMesh sphere = make_icosphere(3, 1.0);
    L2Metric metric({.mass = MassType::Voronoi});
    const double dt = 2e-4;
    const int steps = 500;
    const FlowResult result =
        explicit_euler(sphere, SurfaceAreaEnergy{}, metric, {.time_step = dt, .max_steps = steps});
    ASSERT_EQ(result.status, FlowStatus::MaxSteps);
    const double radius = result.mesh.V.rowwise().norm().mean();
    EXPECT_NEAR(radius, std::sqrt(1.0 - 4 * dt * steps), 2e-3);
}

TEST(Integrators, EnergyDecreasesMonotonicallyUnderImplicitFairing) {
    const TriangleMesh mesh = test::noisy_torus(24, 12, 0.3);
    H1Metric metric({.lambda = 0.01});
    const FlowResult result =
        explicit_euler(mesh, SurfaceAreaEnergy{}, metric, {.time_step = 0.01, .max_steps = 10});
    ASSERT_EQ(result.energy.size(), 11u);
    for (std::size_t k = 1; k < result.energy.size(); ++k) {
        EXPECT_LT(result.energy[k], result.energy[k - 1]);
    }
}

// E = ½‖X‖² scaled so that a unit step overflows after a few steps.
class ExplodingEnergy final : public Energy {
public:
    [[nodiscard]] double value(const TriangleMesh& mesh) const override {
        return 0.5 * mesh.V.squaredNorm();
    }
    [[nodiscard]] VertexField differential(const TriangleMesh& mesh) const override {
        return -1e100 * mesh.V;
    }
};

TEST(Integrators, BlowUpEndsWithStatusAndTheLastFiniteMesh) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.3);
    L2Metric metric;
    const test::FloatingPointTrapsOff overflow_on_purpose;
    const FlowResult result =
        explicit_euler(mesh, ExplodingEnergy{}, metric, {.time_step = 1.0, .max_steps = 200});
    // Positions leave the range operators take (NonFinite) or the masses overflow first
    // (SolverFailed): either way a status, and the last mesh within range is returned.
    EXPECT_FALSE(result.ok()) << to_string(result.status);
    EXPECT_LT(result.steps, 10);
    EXPECT_TRUE(result.mesh.V.allFinite());
    EXPECT_FALSE(result.message.empty());
    EXPECT_EQ(result.energy.size(), static_cast<std::size_t>(result.steps + 1));
}

TEST(Integrators, StoppingRules) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.2);
    H1Metric metric({.lambda = 0.05});
    const FlowResult converged =
        explicit_euler(mesh, SurfaceAreaEnergy{}, metric,
                       {.time_step = 0.05, .max_steps = 1000, .energy_tolerance = 1e-2});
    EXPECT_EQ(converged.status, FlowStatus::Converged);
    EXPECT_LT(converged.steps, 1000);
    int calls = 0;
    const FlowResult cancelled = explicit_euler(
        mesh, SurfaceAreaEnergy{}, metric,
        {.time_step = 0.05, .max_steps = 100, .progress = [&](const FlowProgress& p) {
             EXPECT_EQ(p.step, ++calls);
             EXPECT_NE(p.mesh, nullptr);
             return p.step < 3;
         }});
    EXPECT_EQ(cancelled.status, FlowStatus::Cancelled);
    EXPECT_EQ(cancelled.steps, 3);
    const FlowResult timed =
        explicit_euler(mesh, SurfaceAreaEnergy{}, metric,
                       {.time_step = 0.05, .max_steps = 100000, .max_seconds = 1e-9});
    EXPECT_EQ(timed.status, FlowStatus::TimeLimit);
    EXPECT_EQ(timed.steps, 1);
}

TEST(Integrators, RejectBadOptionsAndNonLinearizableEnergies) {
    const TriangleMesh mesh = make_icosphere(1);
    L2Metric metric;
    EXPECT_THROW((void)explicit_euler(mesh, SurfaceAreaEnergy{}, metric, {.time_step = 0}),
                 InvalidInput);
    EXPECT_THROW((void)explicit_euler(mesh, SurfaceAreaEnergy{}, metric, {.time_step = NAN}),
                 InvalidInput);
    EXPECT_THROW(
        (void)explicit_euler(mesh, SurfaceAreaEnergy{}, metric, {.time_step = 1, .max_steps = -1}),
        InvalidInput);
    EXPECT_THROW((void)implicit_euler(mesh, EnclosedVolumeEnergy{}, metric, {.time_step = 1}),
                 InvalidInput);
}

}  // namespace
}  // namespace genflow
