// SPDX-License-Identifier: MIT
#include "genflow/operators/wave_kernel_signature.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// Σ_i m_i w_i(e) = A Σ_k g(λ_k) (Σ_i m_i φ_k(i)²) / Σ_k g(λ_k) = A: the modes are M-orthonormal.
TEST(WaveKernelSignature, MassWeightedSumIsTheAreaAtEveryEnergy) {
    const LaplacianEigenbasis basis = laplacian_eigenbasis(make_limb(2));
    const Eigen::MatrixXd w = wave_kernel_signature(basis, 20);
    ASSERT_EQ(w.cols(), 20);
    for (Eigen::Index e = 0; e < w.cols(); ++e) {
        EXPECT_NEAR(basis.masses.dot(w.col(e)) / basis.masses.sum(), 1, 1e-10);
        EXPECT_GE(w.col(e).minCoeff(), 0);
    }
}

// Turning, moving and scaling a shape leaves it alone (the eigenpairs scale with the area, and
// the signature is divided by it).
TEST(WaveKernelSignature, IsInvariantUnderSimilarities) {
    const TriangleMesh limb = make_limb(2);
    TriangleMesh moved = limb;
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(1.2, Eigen::Vector3d(1, 2, 0).normalized()).toRotationMatrix();
    moved.V = ((3.5 * limb.V * turn.transpose()).rowwise() + Eigen::RowVector3d(1, -2, 5));
    const Eigen::MatrixXd a = wave_kernel_signature(laplacian_eigenbasis(limb, 60), 30);
    const Eigen::MatrixXd b = wave_kernel_signature(laplacian_eigenbasis(moved, 60), 30);
    EXPECT_LT((a - b).norm() / a.norm(), 1e-8);
}

TEST(WaveKernelSignature, RefusesTooShortASpectrumOrNoEnergy) {
    const LaplacianEigenbasis basis = laplacian_eigenbasis(make_limb(2), 40);
    EXPECT_THROW((void)wave_kernel_signature(basis, 0), InvalidInput);
    LaplacianEigenbasis short_basis = basis;
    short_basis.values = basis.values.head(3);
    short_basis.functions = basis.functions.leftCols(3);
    EXPECT_THROW((void)wave_kernel_signature(short_basis, 10), InvalidInput);
}

}  // namespace
}  // namespace genflow
