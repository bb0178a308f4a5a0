// SPDX-License-Identifier: MIT
#include "genflow/mesh/primitives.h"

#include <gtest/gtest.h>

#include "genflow/exceptions.h"
#include "genflow/mesh/validate.h"
#include "genflow/operators/volume.h"

namespace genflow {
namespace {

TEST(Primitives, IcosphereCountsRadiusAndTopology) {
    for (int level = 0; level <= 3; ++level) {
        const TriangleMesh mesh = make_icosphere(level, 2.5);
        const Eigen::Index faces = 20 * (Eigen::Index{1} << (2 * level));
        EXPECT_EQ(mesh.F.rows(), faces);
        EXPECT_EQ(mesh.V.rows(), faces / 2 + 2);
        EXPECT_NEAR(mesh.V.rowwise().norm().minCoeff(), 2.5, 1e-14);
        EXPECT_NEAR(mesh.V.rowwise().norm().maxCoeff(), 2.5, 1e-14);
        const ValidationReport report = validate(mesh);
        EXPECT_TRUE(report.issues.empty()) << report.issues.front().message;
        EXPECT_EQ(report.genus, 0);
        EXPECT_GT(enclosed_volume(mesh), 0);
    }
}

TEST(Primitives, TorusIsClosedGenusOneOutward) {
    const TriangleMesh mesh = make_torus(20, 9);
    EXPECT_EQ(mesh.V.rows(), 180);
    const ValidationReport report = validate(mesh);
    EXPECT_TRUE(report.issues.empty());
    EXPECT_EQ(report.genus, 1);
    EXPECT_GT(enclosed_volume(mesh), 0);
}

TEST(Primitives, GridHasOneBoundaryLoop) {
    const ValidationReport report = validate(make_grid(5));
    EXPECT_EQ(report.boundary_loops, 1);
    EXPECT_EQ(report.boundary_edges, 20);
    EXPECT_EQ(report.genus, 0);
}

TEST(Primitives, RejectBadParameters) {
    EXPECT_THROW((void)make_icosphere(-1), InvalidInput);
    EXPECT_THROW((void)make_icosphere(2, 0.0), InvalidInput);
    EXPECT_THROW((void)make_torus(2, 5), InvalidInput);
    EXPECT_THROW((void)make_torus(5, 5, 1.0, 1.0), InvalidInput);
    EXPECT_THROW((void)make_grid(0), InvalidInput);
}

TEST(Primitives, NoiseIsReproducible) {
    const TriangleMesh a = add_noise(make_icosphere(1), 0.01, 7);
    const TriangleMesh b = add_noise(make_icosphere(1), 0.01, 7);
    const TriangleMesh c = add_noise(make_icosphere(1), 0.01, 8);
    EXPECT_EQ(a.V, b.V);
    EXPECT_NE(a.V, c.V);
}

}  // namespace
}  // namespace genflow
