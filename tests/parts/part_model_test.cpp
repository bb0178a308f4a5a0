// SPDX-License-Identifier: MIT
// The part model: what fits a template, and the depths of a tree and of a forest of parts.
#include "genflow/parts/part_model.h"

#include <gtest/gtest.h>

#include <vector>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

TEST(PartModel, RejectsModelsThatDoNotFit) {
    const TriangleMesh mesh = make_limb(2);
    PartModel model = test::two_part_arm(mesh);
    EXPECT_NO_THROW(check_part_model(model, mesh.V.rows()));
    EXPECT_THROW(check_part_model(model, mesh.V.rows() + 1), InvalidInput);  // wrong count
    PartModel cycle = model;
    cycle.parts[0].parent = 1;  // no root, a cycle
    EXPECT_THROW(check_part_model(cycle, mesh.V.rows()), InvalidInput);
    PartModel two_roots = model;  // a forest fits (the libigl elephant's legs and spine)
    two_roots.parts[1].parent = -1;
    EXPECT_NO_THROW(check_part_model(two_roots, mesh.V.rows()));
    PartModel bad_sum = model;
    bad_sum.weights(3, 0) = 0.5;
    bad_sum.weights(3, 1) = 0.2;
    EXPECT_THROW(check_part_model(bad_sum, mesh.V.rows()), InvalidInput);
    EXPECT_THROW((void)weights_from_labels(Eigen::VectorXi::Constant(4, 2), 2), InvalidInput);
}

// One root moves with the whole template; several hang from it, one level down, each about
// its own joint.
TEST(PartModel, DepthsOfATreeAndOfAForest) {
    const TriangleMesh mesh = make_limb(2);
    PartModel model = test::two_part_arm(mesh);
    EXPECT_EQ(part_depths(model), (std::vector<int>{0, 1}));
    model.parts.push_back({"hand", 1, Eigen::Vector3d(1.8, 0, 0)});
    model.weights.conservativeResize(Eigen::NoChange, 3);
    model.weights.col(2).setZero();
    EXPECT_EQ(part_depths(model), (std::vector<int>{0, 1, 2}));
    model.parts[1].parent = -1;
    EXPECT_EQ(part_depths(model), (std::vector<int>{1, 1, 2}));
}

}  // namespace
}  // namespace genflow
