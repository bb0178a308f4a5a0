// SPDX-License-Identifier: MIT
#include "genflow/matching/carry_attributes.h"

#include <gtest/gtest.h>

#include "genflow/exceptions.h"
#include "genflow/matching/correspondence.h"
#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

// Onto itself through its own closest points, every vertex gets its own attributes back.
TEST(CarryAttributes, OntoItselfEveryVertexKeepsItsOwn) {
    const TriangleMesh mesh = make_icosphere(2);
    VertexAttributes attributes;
    attributes.colors = VertexColors::Zero(mesh.V.rows(), 3);
    attributes.colors.col(1) = (100 * (mesh.V.col(2).array() + 1)).cast<std::uint8_t>();
    attributes.scalars.emplace_back("height", mesh.V.col(2));
    attributes.scalars.emplace_back("side", (mesh.V.col(0).array() > 0).cast<double>());
    const VertexAttributes carried =
        carry_attributes(mesh, attributes, mesh, closest_points(mesh.V, mesh));
    EXPECT_EQ(carried.colors, attributes.colors);
    ASSERT_EQ(carried.scalars.size(), 2U);
    EXPECT_LT((carried.scalars[0].second - attributes.scalars[0].second).cwiseAbs().maxCoeff(),
              1e-12);
    EXPECT_EQ(carried.scalars[1].second, attributes.scalars[1].second);
}

// Onto a finer sampling of the same sphere: a value is interpolated (within the faces'
// variation), a label is one of the corners' labels, never a blend.
TEST(CarryAttributes, InterpolatesValuesAndTakesLabelsWhole) {
    const TriangleMesh coarse = make_icosphere(2);
    const TriangleMesh fine = make_icosphere(4);
    VertexAttributes attributes;
    attributes.scalars.emplace_back("height", coarse.V.col(2));
    attributes.scalars.emplace_back("side", (coarse.V.col(0).array() > 0).cast<double>());
    const VertexAttributes carried =
        carry_attributes(coarse, attributes, fine, closest_points(coarse.V, fine));
    const Eigen::VectorXd& height = carried.scalars[0].second;
    EXPECT_LT((height - fine.V.col(2)).cwiseAbs().maxCoeff(), 0.05);
    for (Eigen::Index t = 0; t < fine.V.rows(); ++t) {
        const double side = carried.scalars[1].second[t];
        EXPECT_TRUE(side == 0 || side == 1) << side;
        if (std::abs(fine.V(t, 0)) > 0.2) {
            EXPECT_EQ(side, fine.V(t, 0) > 0 ? 1 : 0);
        }
    }
    EXPECT_THROW((void)carry_attributes(coarse, attributes, fine, {}), InvalidInput);
}

}  // namespace
}  // namespace genflow
