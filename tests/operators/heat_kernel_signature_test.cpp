// SPDX-License-Identifier: MIT
#include "genflow/operators/heat_kernel_signature.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/mass_matrix.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// Σ_i m_i h_i(t) = A Σ_k e^{−λt} (Σ_i m_i φ_k(i)²) / Σ_k e^{−λt} = A: the modes are
// M-orthonormal.
TEST(HeatKernelSignature, MassWeightedSumIsOneAtEveryTime) {
    for (const TriangleMesh& mesh :
         {test::noisy_icosphere(2, 0.3), test::noisy_torus(12, 6, 0.2), test::jittered_grid(6)}) {
        const Eigen::MatrixXd h = heat_kernel_signature(mesh);
        const Eigen::VectorXd m = lumped_masses(mesh, MassType::Barycentric);
        ASSERT_EQ(h.cols(), static_cast<Eigen::Index>(default_heat_kernel_times().size()));
        for (Eigen::Index t = 0; t < h.cols(); ++t) {
            EXPECT_NEAR(m.dot(h.col(t)) / m.sum(), 1, 1e-10);
            EXPECT_GT(h.col(t).minCoeff(), 0);
        }
    }
}

// On a round sphere every point is alike and the heat kernel's diagonal is the heat trace over
// the area: h = 1 at every time.
TEST(HeatKernelSignature, IsOneEverywhereOnASphere) {
    const TriangleMesh sphere = make_icosphere(3, 2.0);
    const Eigen::MatrixXd h = heat_kernel_signature(sphere, {1e-2, 1e-1});
    // Measured 0.018 and 7e-4: the error is the mesh's (642 vertices, about 1.6e-3·A each),
    // largest where heat has spread over few faces.
    EXPECT_LT(h.col(0).array().log().abs().maxCoeff(), 0.03);
    EXPECT_LT(h.col(1).array().log().abs().maxCoeff(), 0.002);
}

TEST(HeatKernelSignature, DoesNotChangeUnderRigidMotionAndScaling) {
    const TriangleMesh mesh = make_limb(2);
    TriangleMesh moved = mesh;
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
    moved.V =
        ((7.5 * mesh.V * rotation.transpose()).rowwise() + Eigen::RowVector3d(3, -40, 2)).eval();
    const Eigen::MatrixXd h = heat_kernel_signature(mesh);
    const Eigen::MatrixXd h_moved = heat_kernel_signature(moved);
    EXPECT_LT((h_moved.array() / h.array()).log().abs().maxCoeff(), 1e-8);
}

// At small times h ≈ 1 + (K − K̄)·t/3: on an ellipsoid (2, 1, 1) the tips of the long axis
// (K = 4) keep more heat than the mean (K̄ = 4π/A ≈ 0.58), the equator (K = 1/4) less.
TEST(HeatKernelSignature, IsLargerWhereTheGaussianCurvatureIsLarger) {
    const TriangleMesh ellipsoid = make_ellipsoid(3, Eigen::Vector3d(2, 1, 1));
    const Eigen::MatrixXd h = heat_kernel_signature(ellipsoid, {1e-2, 2e-2, 5e-2});
    Eigen::Index tip = 0;
    Eigen::Index equator = 0;
    ellipsoid.V.col(0).maxCoeff(&tip);
    ellipsoid.V.col(0).cwiseAbs().minCoeff(&equator);
    for (Eigen::Index t = 0; t < h.cols(); ++t) {
        EXPECT_GT(h(tip, t), 1.1);       // measured 1.13, 1.20, 1.27 (first order: 1.24, 1.49, ...)
        EXPECT_LT(h(equator, t), 0.97);  // measured 0.95, 0.94, 0.89
    }
}

TEST(HeatKernelSignature, LeavesZeroMassVerticesOutAndRejectsBadInput) {
    TriangleMesh mesh = test::noisy_icosphere(1, 0.1);
    mesh.V.conservativeResize(mesh.V.rows() + 1, 3);
    mesh.V.row(mesh.V.rows() - 1) = Eigen::RowVector3d(5, 5, 5);  // referenced by no face
    const Eigen::MatrixXd h = heat_kernel_signature(mesh);
    EXPECT_EQ(h.row(h.rows() - 1).cwiseAbs().maxCoeff(), 0);
    EXPECT_GT(h.topRows(h.rows() - 1).minCoeff(), 0);

    EXPECT_THROW((void)heat_kernel_signature(mesh, {0.01, 0}), InvalidInput);
    EXPECT_THROW((void)heat_kernel_signature(mesh, {std::nan("")}), InvalidInput);
    EXPECT_THROW((void)heat_kernel_signature(make_icosphere(5)), InvalidInput);  // 10242 > 4000
    TriangleMesh flat = mesh;
    flat.V.setZero();
    EXPECT_THROW((void)heat_kernel_signature(flat), InvalidInput);
}

}  // namespace
}  // namespace genflow
