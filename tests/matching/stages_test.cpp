// SPDX-License-Identifier: MIT
// The matcher's first stages on a generated pair: prepare() (rigid starts, pyramid) and the
// flow of one level (LevelFlows).
#include <gtest/gtest.h>

#include <atomic>

#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"
#include "matching/level_flow.h"
#include "matching/prepare.h"

namespace genflow::detail {
namespace {

// The generated limb and another sampling of it, moved: a pair alike up to a similarity.
struct MovedLimb {
    TriangleMesh template_mesh = make_limb(4);
    TriangleMesh target = make_limb(4, 5);
    MovedLimb() { target.V.rowwise() += Eigen::RowVector3d(0.3, -0.2, 0.1); }
};

// Finest level first, the inputs themselves; each coarser template about a quarter of the one
// before and its vertices a subset of the template's; the coarsest near coarse_vertices.
TEST(Prepare, BuildsANestedPyramidAndTheRigidStarts) {
    const MovedLimb pair;
    MatchOptions options;
    options.coarse_vertices = 300;
    options.alignment_candidates = 3;
    const Prepared prepared = prepare(pair.template_mesh, pair.target, options);
    ASSERT_GE(prepared.pyramid.size(), 2U);
    EXPECT_EQ(prepared.pyramid.front().template_mesh.V, pair.template_mesh.V);
    EXPECT_EQ(prepared.pyramid.front().target.V, pair.target.V);
    for (std::size_t l = 1; l < prepared.pyramid.size(); ++l) {
        const Level& level = prepared.pyramid[l];
        const Eigen::Index finer = prepared.pyramid[l - 1].template_mesh.V.rows();
        EXPECT_NEAR(static_cast<double>(level.template_mesh.V.rows()), finer / 4.0, 0.1 * finer);
        ASSERT_EQ(level.original_vertex.size(),
                  static_cast<std::size_t>(level.template_mesh.V.rows()));
        for (std::size_t k = 0; k < level.original_vertex.size(); ++k) {
            EXPECT_EQ(level.template_mesh.V.row(static_cast<Eigen::Index>(k)),
                      pair.template_mesh.V.row(level.original_vertex[k]));
        }
    }
    EXPECT_LE(prepared.pyramid.back().template_mesh.V.rows(), 2 * options.coarse_vertices);
    EXPECT_EQ(prepared.starts.size(), 3U);
    EXPECT_FALSE(prepared.volume_scale.has_value());  // a smooth target: the areas hold

    options.align = false;  // the inputs as they are placed
    const Prepared unaligned = prepare(pair.template_mesh, pair.target, options);
    ASSERT_EQ(unaligned.starts.size(), 1U);
    EXPECT_EQ(unaligned.starts.front().matrix(), Eigen::Matrix4d::Identity());
}

// A level's flow lowers d_H at every step from the template's place; a progress call that says stop
// cancels it and every other flow that shares the flag.
TEST(LevelFlows, LowerTheDistanceAndStopWhenCancelled) {
    const MovedLimb pair;
    MatchOptions options;
    options.coarse_vertices = 300;
    const Prepared prepared = prepare(pair.template_mesh, pair.target, options);
    std::atomic<bool> cancelled = false;
    const LevelFlows flows(prepared.pyramid, options, bounding_box_diagonal(pair.target),
                           cancelled);
    const int coarsest = static_cast<int>(prepared.pyramid.size()) - 1;
    const Level& level = prepared.pyramid.back();
    const FlowResult flow = flows.flow(coarsest, level.template_mesh, 40, {}, MatchPrior::H1);
    ASSERT_TRUE(flow.ok()) << flow.message;
    for (std::size_t k = 1; k < flow.energy.size(); ++k) {
        EXPECT_LT(flow.energy[k], flow.energy[k - 1]) << k;
    }
    EXPECT_LT(flow.energy.back(), 0.8 * flow.energy.front());
    EXPECT_NEAR(flow.energy.front(),
                flows.distance_to_target(level, 1, {}).value(level.template_mesh),
                1e-12 * flow.energy.front());
    EXPECT_FALSE(cancelled);

    options.progress = [](const MatchProgress& progress) { return progress.step < 3; };
    const LevelFlows stopping(prepared.pyramid, options, bounding_box_diagonal(pair.target),
                              cancelled);
    const FlowResult stopped = stopping.flow(coarsest, level.template_mesh, 40, {}, MatchPrior::H1);
    EXPECT_EQ(stopped.status, FlowStatus::Cancelled);
    EXPECT_EQ(stopped.steps, 3);
    EXPECT_TRUE(cancelled);
}

}  // namespace
}  // namespace genflow::detail
