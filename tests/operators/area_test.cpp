// SPDX-License-Identifier: MIT
#include "genflow/operators/area.h"

#include <gtest/gtest.h>

#include <numbers>

#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

TEST(Area, OfAKnownTriangle) {
    TriangleMesh mesh;
    mesh.V.resize(3, 3);
    mesh.V << 0, 0, 0, 3, 0, 0, 0, 4, 0;
    mesh.F.resize(1, 3);
    mesh.F << 0, 1, 2;
    EXPECT_DOUBLE_EQ(surface_area(mesh), 6.0);
    EXPECT_DOUBLE_EQ(surface_area(make_grid(7, 2.0)), 4.0);
}

TEST(Area, OfIcospheresConvergesQuadraticallyTo4PiR2) {
    const double radius = 1.7;
    const double exact = 4 * std::numbers::pi * radius * radius;
    double previous_error = 0;
    for (int level = 1; level <= 5; ++level) {
        const double error = exact - surface_area(make_icosphere(level, radius));
        EXPECT_GT(error, 0);  // inscribed polyhedron
        if (level > 2) {
            // Halving the edge length divides the error by 4: second order.
            EXPECT_NEAR(previous_error / error, 4.0, 0.1) << "level " << level;
        }
        previous_error = error;
    }
    EXPECT_LT(previous_error / exact, 1e-3);
}

TEST(Area, GradientMatchesCentralFiniteDifferences) {
    for (const TriangleMesh& mesh :
         {test::noisy_icosphere(1, 0.2), test::noisy_torus(8, 5, 0.2), test::jittered_grid(3)}) {
        const VertexField fd = test::finite_difference_gradient(
            [](const TriangleMesh& m) { return surface_area(m); }, mesh);
        EXPECT_LT(test::relative_error(surface_area_gradient(mesh), fd), 1e-6);
    }
}

TEST(Area, GradientOfAFlatGridIsInPlaneAndVanishesInside) {
    const TriangleMesh mesh = test::jittered_grid(4);
    const VertexField gradient = surface_area_gradient(mesh);
    EXPECT_LT(gradient.col(2).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_GT(gradient.norm(), 0.1);  // the boundary pulls inward
}

}  // namespace
}  // namespace genflow
