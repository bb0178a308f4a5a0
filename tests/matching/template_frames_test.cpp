// SPDX-License-Identifier: MIT
#include "genflow/matching/template_frames.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numeric>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

// A coarse level moved rigidly carries the whole template along exactly (transfer() is exact
// for rigid motions); the template's own level comes back as it is.
TEST(TemplateFrames, CarriesACoarseLevelsMotionToEveryTemplateVertex) {
    const TriangleMesh limb = make_limb(3);
    const CoarseMesh coarse = coarsen(limb, 100);
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const Eigen::RowVector3d shift(0.5, -1, 2);
    const auto moved = [&](const Eigen::MatrixX3d& V) {
        return Eigen::MatrixX3d((V * rotation.transpose()).rowwise() + shift);
    };
    TemplateFrames frames(limb);
    for (int repeat = 0; repeat < 2; ++repeat) {  // the second frame reuses the embedding
        const TriangleMesh frame =
            frames(TriangleMesh{moved(coarse.mesh.V), coarse.mesh.F}, coarse.fine_vertex);
        ASSERT_EQ(frame.F, limb.F);
        EXPECT_LT((frame.V - moved(limb.V)).cwiseAbs().maxCoeff(), 1e-9);
    }
    std::vector<Eigen::Index> identity(static_cast<std::size_t>(limb.V.rows()));
    std::iota(identity.begin(), identity.end(), 0);
    const TriangleMesh same{moved(limb.V), limb.F};
    EXPECT_EQ(frames(same, identity).V, same.V);
}

TEST(TemplateFrames, RefusesVerticesThatAreNotTheTemplates) {
    const TriangleMesh limb = make_limb(2);
    const CoarseMesh coarse = coarsen(limb, 50);
    TemplateFrames frames(limb);
    std::vector<Eigen::Index> beyond = coarse.fine_vertex;
    beyond.back() = limb.V.rows();
    EXPECT_THROW((void)frames(coarse.mesh, beyond), InvalidInput);
    beyond.pop_back();  // one short
    EXPECT_THROW((void)frames(coarse.mesh, beyond), InvalidInput);
}

}  // namespace
}  // namespace genflow
