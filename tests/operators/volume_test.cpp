// SPDX-License-Identifier: MIT
#include "genflow/operators/volume.h"

#include <gtest/gtest.h>

#include <numbers>

#include "genflow/mesh/primitives.h"
#include "genflow/operators/area.h"
#include "genflow/operators/normals.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

TEST(Volume, OfIcospheresConvergesQuadraticallyTo4Thirds_PiR3) {
    const double radius = 0.6;
    const double exact = 4.0 / 3.0 * std::numbers::pi * std::pow(radius, 3);
    double previous_error = 0;
    for (int level = 1; level <= 5; ++level) {
        const double error = exact - enclosed_volume(make_icosphere(level, radius));
        EXPECT_GT(error, 0);
        if (level > 2) {
            EXPECT_NEAR(previous_error / error, 4.0, 0.1) << "level " << level;
        }
        previous_error = error;
    }
    EXPECT_LT(previous_error / exact, 1e-3);
}

TEST(Volume, OfATorusApproaches2Pi2Rr2) {
    const double exact = 2 * std::numbers::pi * std::numbers::pi * 1.0 * 0.4 * 0.4;
    EXPECT_NEAR(enclosed_volume(make_torus(200, 100)), exact, 2e-3 * exact);
}

TEST(Volume, IsTranslationInvariantOnClosedMeshesAndFlipsWithOrientation) {
    TriangleMesh mesh = test::noisy_torus(12, 8, 0.2);
    const double volume = enclosed_volume(mesh);
    mesh.V.rowwise() += Eigen::RowVector3d(3, -7, 11);
    EXPECT_NEAR(enclosed_volume(mesh), volume, 1e-12 * std::abs(volume));
    mesh.F.col(1).swap(mesh.F.col(2));
    EXPECT_NEAR(enclosed_volume(mesh), -volume, 1e-12 * std::abs(volume));
}

TEST(Volume, GradientMatchesCentralFiniteDifferences) {
    for (const TriangleMesh& mesh : {test::noisy_icosphere(1, 0.2), test::noisy_torus(8, 5, 0.2)}) {
        const VertexField fd = test::finite_difference_gradient(
            [](const TriangleMesh& m) { return enclosed_volume(m); }, mesh);
        EXPECT_LT(test::relative_error(enclosed_volume_gradient(mesh), fd), 1e-6);
    }
}

TEST(Volume, GradientIsAThirdOfTheAreaWeightedNormalOnClosedMeshes) {
    const TriangleMesh mesh = test::noisy_icosphere(2, 0.2);
    const VertexField gradient = enclosed_volume_gradient(mesh);
    // ñ_i = Σ A_f n_f: rebuild it from the unit normals and the face areas.
    const Eigen::MatrixX3d face_n = face_normals(mesh);
    const Eigen::VectorXd areas = face_areas(mesh);
    VertexField weighted = VertexField::Zero(mesh.V.rows(), 3);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            weighted.row(mesh.F(f, k)) += areas[f] * face_n.row(f);
        }
    }
    EXPECT_LT(test::relative_error(gradient, weighted / 3), 1e-13);
}

}  // namespace
}  // namespace genflow
