// SPDX-License-Identifier: MIT
#include "genflow/smoothing/smoothing.h"

#include <gtest/gtest.h>

#include "genflow/energies/surface_area_energy.h"
#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/operators/area.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/volume.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// RMS distance to the clean sphere of radius 1.
double sphere_noise(const TriangleMesh& mesh) {
    return std::sqrt(
        (mesh.V.rowwise().norm().array() - mesh.V.rowwise().norm().mean()).square().mean());
}

TEST(Smoothing, EveryMethodRemovesNoiseFromASphere) {
    const TriangleMesh noisy = test::noisy_icosphere(3, 0.2, 5);
    const double before = sphere_noise(noisy);
    for (const auto& method :
         {mean_curvature_flow, implicit_fairing, higher_order_fairing, volume_controlled_fairing}) {
        const FlowResult result = method(noisy, {.time_step = 1.0, .steps = 5});
        ASSERT_TRUE(result.ok()) << result.message;
        EXPECT_LT(sphere_noise(result.mesh), 0.5 * before);
        EXPECT_LT(result.energy.back(), result.energy.front());
    }
}

TEST(Smoothing, MeanCurvatureFlowClampsItsStepToStability) {
    const TriangleMesh noisy = test::noisy_icosphere(3, 0.3, 5);
    const FlowResult result = mean_curvature_flow(noisy, {.time_step = 1000.0, .steps = 20});
    EXPECT_TRUE(result.ok()) << result.message;
    EXPECT_TRUE(result.mesh.V.allFinite());
}

TEST(Smoothing, FixBoundaryKeepsBoundaryVerticesExactly) {
    TriangleMesh grid = test::jittered_grid(10);
    grid = add_noise(grid, 0.02, 3);
    const FlowResult fixed =
        implicit_fairing(grid, {.time_step = 5.0, .steps = 3, .fix_boundary = true});
    const FlowResult free = implicit_fairing(grid, {.time_step = 5.0, .steps = 3});
    int boundary = 0;
    for (Eigen::Index i = 0; i < grid.V.rows(); ++i) {
        const double x = make_grid(10).V(i, 0);
        const double y = make_grid(10).V(i, 1);
        if (x == 0 || x == 1 || y == 0 || y == 1) {
            ++boundary;
            EXPECT_EQ(fixed.mesh.V.row(i), grid.V.row(i)) << "vertex " << i;
        }
    }
    EXPECT_EQ(boundary, 40);
    EXPECT_GT((free.mesh.V - fixed.mesh.V).norm(), 1e-3);  // without it the boundary moves
}

TEST(Smoothing, WorksOnOpenMultiComponentMeshesWithSlivers) {
    TriangleMesh mesh = test::jittered_grid(8);
    TriangleMesh second = make_torus(12, 6);
    const Eigen::Index n = mesh.V.rows();
    mesh.V.conservativeResize(n + second.V.rows(), 3);
    mesh.V.bottomRows(second.V.rows()) = second.V.rowwise() + Eigen::RowVector3d(3, 0, 0);
    mesh.F.conservativeResize(mesh.F.rows() + second.F.rows(), 3);
    mesh.F.bottomRows(second.F.rows()) = second.F.array() + static_cast<int>(n);
    mesh.V(10, 1) = mesh.V(11, 1) + 1e-9;  // a needle
    for (const auto& method :
         {mean_curvature_flow, implicit_fairing, higher_order_fairing, volume_controlled_fairing}) {
        for (const bool fix : {false, true}) {
            const FlowResult result =
                method(mesh, {.time_step = 2.0, .steps = 3, .fix_boundary = fix});
            EXPECT_TRUE(result.ok()) << result.message;
            EXPECT_TRUE(result.mesh.V.allFinite());
        }
    }
}

TEST(Smoothing, IsScaleFree) {
    const TriangleMesh mesh = test::noisy_torus(20, 10, 0.2);
    TriangleMesh scaled = mesh;
    scaled.V *= 1000.0;
    const FlowResult a = implicit_fairing(mesh, {.time_step = 3.0, .steps = 2});
    const FlowResult b = implicit_fairing(scaled, {.time_step = 3.0, .steps = 2});
    EXPECT_LT(test::relative_error(b.mesh.V / 1000.0, a.mesh.V), 1e-10);
}

// The frozen metric: the input's H1 metric, factored once, for every step, which is then
// x ← x − dt·G₀⁻¹·dA/dx(x); its first step is implicit fairing's.
TEST(Smoothing, AFrozenMetricIsTheInputsForEveryStep) {
    const TriangleMesh mesh = test::noisy_torus(20, 10, 0.2);
    const double h = mean_edge_length(mesh);
    const double dt = 0.5 * h * h;
    H1Metric metric({.lambda = dt});
    metric.update(mesh);
    Eigen::MatrixX3d x = mesh.V;
    for (int step = 0; step < 4; ++step) {
        x -= dt * metric.gradient(SurfaceAreaEnergy().differential(TriangleMesh{x, mesh.F}));
    }
    const FlowResult frozen =
        implicit_fairing(mesh, {.time_step = 0.5, .steps = 4, .freeze_metric = true});
    EXPECT_LT(test::relative_error(frozen.mesh.V, x), 1e-12);
    const FlowResult one = implicit_fairing(mesh, {.time_step = 0.5, .steps = 1});
    const FlowResult frozen_one =
        implicit_fairing(mesh, {.time_step = 0.5, .steps = 1, .freeze_metric = true});
    EXPECT_EQ(frozen_one.mesh.V, one.mesh.V);
    const FlowResult moving = implicit_fairing(mesh, {.time_step = 0.5, .steps = 4});
    EXPECT_GT(test::relative_error(frozen.mesh.V, moving.mesh.V), 1e-6);  // another flow
    for (std::size_t k = 1; k < frozen.energy.size(); ++k) {
        EXPECT_LT(frozen.energy[k], frozen.energy[k - 1]);  // still a descent of the area
    }
}

TEST(Smoothing, RefusesBadMeshesAndOptions) {
    TriangleMesh mesh = make_icosphere(1);
    EXPECT_THROW((void)implicit_fairing(mesh, {.time_step = -1}), InvalidInput);
    EXPECT_THROW((void)higher_order_fairing(mesh, {.mu = -1}), InvalidInput);
    mesh.V(0, 0) = NAN;
    EXPECT_THROW((void)implicit_fairing(mesh, {}), InvalidInput);
    EXPECT_THROW((void)mean_curvature_flow(TriangleMesh{}, {}), InvalidInput);
    // Collinear corners: edges of positive length, no area to flow.
    TriangleMesh flat{(Eigen::MatrixX3d(3, 3) << 0, 0, 0, 1, 0, 0, 2, 0, 0).finished(),
                      (Eigen::MatrixX3i(1, 3) << 0, 1, 2).finished()};
    try {
        (void)volume_controlled_fairing(flat, {});
        ADD_FAILURE() << "a flat mesh was smoothed";
    } catch (const InvalidInput& error) {
        EXPECT_STREQ(error.what(), "volume_controlled_fairing: every face has zero area");
    }
    flat.F.resize(0, 3);
    EXPECT_THROW((void)implicit_fairing(flat, {}), InvalidInput);
    flat.F = (Eigen::MatrixX3i(1, 3) << 0, 1, 3).finished();
    EXPECT_THROW((void)implicit_fairing(flat, {}), InvalidInput);  // an index out of range
}

}  // namespace
}  // namespace genflow
