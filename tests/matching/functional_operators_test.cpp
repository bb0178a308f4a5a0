// SPDX-License-Identifier: MIT
#include "matching/functional_operators.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "genflow/mesh/primitives.h"
#include "genflow/operators/laplacian_eigenbasis.h"

namespace genflow {
namespace {

// `mesh` reflected across the plane x = 0, its faces turned so that they face outward again:
// the same surface, with left and right exchanged.
TriangleMesh reflected(const TriangleMesh& mesh) {
    TriangleMesh mirror = mesh;
    mirror.V.col(0) *= -1;
    mirror.F.col(1).swap(mirror.F.col(2));
    return mirror;
}

TriangleMesh turned_and_scaled(const TriangleMesh& mesh) {
    TriangleMesh moved = mesh;
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(2.1, Eigen::Vector3d(0, 1, 3).normalized()).toRotationMatrix();
    moved.V = (2.5 * mesh.V * turn.transpose()).rowwise() + Eigen::RowVector3d(4, 0, -1);
    return moved;
}

struct LimbFunctions {
    TriangleMesh limb = make_limb(2);
    LaplacianEigenbasis basis = laplacian_eigenbasis(limb, 12);
    // Two smooth functions with gradients that cross.
    Eigen::VectorXd f = basis.functions.col(2) + 0.5 * basis.functions.col(5);
    Eigen::VectorXd g = basis.functions.col(3);
};

TEST(FunctionalOperators, MultiplicationByOneIsTheIdentity) {
    const LimbFunctions s;
    const Eigen::MatrixXd op = detail::multiplication_operator(
        s.basis.functions, s.basis.masses, Eigen::VectorXd::Ones(s.limb.V.rows()));
    EXPECT_LT((op - Eigen::MatrixXd::Identity(12, 12)).norm(), 1e-10);
    const Eigen::MatrixXd by_f =
        detail::multiplication_operator(s.basis.functions, s.basis.masses, s.f);
    EXPECT_LT((by_f - by_f.transpose()).norm(), 1e-12 * by_f.norm());
}

// The orientation operator is antisymmetric, unchanged by rotations and uniform scaling (∇f
// scales as 1/s and the edges as s), and negated by a reflection (the same functions on the
// mirrored surface: its faces' orientation is reversed).
TEST(FunctionalOperators, OrientationOperatorChangesSignUnderReflectionsOnly) {
    const LimbFunctions s;
    const Eigen::MatrixXd op = detail::orientation_operator(s.limb, s.basis.functions, s.f);
    EXPECT_GT(op.norm(), 1e-3);
    EXPECT_LT((op + op.transpose()).norm(), 1e-12 * op.norm());
    const Eigen::MatrixXd moved =
        detail::orientation_operator(turned_and_scaled(s.limb), s.basis.functions, s.f);
    EXPECT_LT((moved - op).norm(), 1e-9 * op.norm());
    const Eigen::MatrixXd mirror =
        detail::orientation_operator(reflected(s.limb), s.basis.functions, s.f);
    EXPECT_LT((mirror + op).norm(), 1e-9 * op.norm());
}

// The signed descriptor ⟨n, ∇f × ∇g⟩ likewise, and it is antisymmetric in f and g; dimension:
// 1/area, so scaling the surface by 2.5 divides it by 6.25.
TEST(FunctionalOperators, SignedDescriptorChangesSignUnderReflectionsOnly) {
    const LimbFunctions s;
    const auto descriptor = [&](const TriangleMesh& mesh, const Eigen::VectorXd& a,
                                const Eigen::VectorXd& b) {
        return detail::signed_descriptor(mesh, s.basis.functions, s.basis.masses, a, b);
    };
    const Eigen::VectorXd d = descriptor(s.limb, s.f, s.g);
    EXPECT_GT(d.norm(), 1e-3);
    EXPECT_LT((descriptor(s.limb, s.g, s.f) + d).norm(), 1e-12 * d.norm());
    EXPECT_LT((6.25 * descriptor(turned_and_scaled(s.limb), s.f, s.g) - d).norm(), 1e-9 * d.norm());
    EXPECT_LT((descriptor(reflected(s.limb), s.f, s.g) + d).norm(), 1e-9 * d.norm());
}

}  // namespace
}  // namespace genflow
