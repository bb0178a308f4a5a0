// SPDX-License-Identifier: MIT
// The quasi-articulated metric (paper eqs. 17-19) and the part weights blended across seams.
#include "genflow/parts/quasi_articulated_metric.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mesh_size.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// Blended weights are a partition of unity that falls from one part to the other across the
// seam, over about blend_edges edge lengths, and stay hard far from it; soft rows are kept.
TEST(BlendPartWeights, FallAcrossTheSeamAndKeepSoftRows) {
    const TriangleMesh arm = make_limb(3);
    PartModel parts = test::two_part_arm(arm);
    parts.weights.row(0) << 0.3, 0.7;  // a soft row, someone's choice
    const double h = mean_edge_length(arm);
    const Eigen::MatrixXd blended = blend_part_weights(arm, parts.weights, 3);
    ASSERT_EQ(blended.rows(), arm.V.rows());
    EXPECT_LT((blended.rowwise().sum().array() - 1).abs().maxCoeff(), 1e-12);
    EXPECT_GE(blended.minCoeff(), 0.0);
    EXPECT_EQ(blended.row(0), parts.weights.row(0));
    int softened = 0;
    for (Eigen::Index i = 1; i < arm.V.rows(); ++i) {
        const double from_seam = std::abs(arm.V(i, 0) - 1.0);
        if (from_seam > 12 * h) {
            EXPECT_NEAR(blended(i, 1), parts.weights(i, 1), 0.02) << i;
        }
        if (from_seam < h) {
            softened += blended(i, 1) > 0.05 && blended(i, 1) < 0.95 ? 1 : 0;
        }
    }
    EXPECT_GT(softened, 0);
    EXPECT_EQ(blend_part_weights(arm, parts.weights, 0), parts.weights);
    EXPECT_THROW((void)blend_part_weights(arm, parts.weights.topRows(4), 3), InvalidInput);
    EXPECT_THROW((void)blend_part_weights(arm, parts.weights, -1), InvalidInput);
}

// As a tree (upper arm the root, the forearm its child) or as a forest (both roots, each about
// its own joint), the two-part arm's metric is SPD and bends at the elbow.
class QuasiArticulatedMetricOfTreeAndForest : public ::testing::TestWithParam<bool> {};

TEST_P(QuasiArticulatedMetricOfTreeAndForest, IsSPDAndBendsAtTheJoint) {
    const TriangleMesh arm = make_limb(3);
    PartModel parts = test::two_part_arm(arm);
    if (GetParam()) {
        parts.parts[1].parent = -1;
    }
    SubspaceMetric metric = quasi_articulated_metric(arm, parts);
    metric.update(arm);
    const VertexField U = test::noisy_icosphere(3, 0.3, 4).V.topRows(arm.V.rows());
    EXPECT_LT(test::relative_error(metric.gradient(metric.apply(U)), U), 1e-10);
    EXPECT_GT((U.array() * metric.apply(U).array()).sum(), 0);

    // Bending the lower part about the joint is cheap (its metric norm is a small multiple
    // of its L2 norm); a bulge of the middle, which no part motion explains, is not.
    const auto cost = [&](const VertexField& v) {
        const VertexField Mv = (v.array().colwise() * metric.masses().array()).matrix();
        return (v.array() * metric.apply(v).array()).sum() / (v.array() * Mv.array()).sum();
    };
    VertexField bend(arm.V.rows(), 3);
    VertexField bulge(arm.V.rows(), 3);
    for (Eigen::Index i = 0; i < arm.V.rows(); ++i) {
        const Eigen::Vector3d x = arm.V.row(i).transpose();
        const double lower = std::clamp((x.x() - 0.8) / 0.4, 0.0, 1.0);
        bend.row(i) = lower * Eigen::Vector3d::UnitZ().cross(x - Eigen::Vector3d(1, 0, 0));
        bulge.row(i) = std::cos(x.x()) * Eigen::Vector3d(0, x.y(), x.z());
    }
    EXPECT_LT(cost(bend), 0.1);
    EXPECT_GT(cost(bulge), 0.5);
}

INSTANTIATE_TEST_SUITE_P(QuasiArticulatedMetric, QuasiArticulatedMetricOfTreeAndForest,
                         ::testing::Bool(), [](const ::testing::TestParamInfo<bool>& forest) {
                             return forest.param ? "Forest" : "Tree";
                         });

// A chain of 17 parts along a sphere (as bench/flow_bench's BM_ArticulatedMetricUpdate): each
// limb's fields nearly repeat its parent's over the subtree they share, and the blended
// weights reach everywhere, so the Gram matrix of all 55 fields is far from diagonal. The
// Gram–Schmidt on it still gives M-orthonormal blocks, to 3e-10 (it runs on the Gram matrix,
// whose rounding the nearly repeated fields magnify), and gradient() inverts apply().
TEST(QuasiArticulatedMetric, DeepChainKeepsOrthonormalBlocks) {
    const TriangleMesh sphere = make_icosphere(3);
    constexpr int kParts = 17;
    Eigen::VectorXi labels(sphere.V.rows());
    PartModel chain;
    for (int k = 0; k < kParts; ++k) {
        chain.parts.push_back(
            {"part" + std::to_string(k), k - 1, Eigen::Vector3d(-1 + 2.0 * k / kParts, 0, 0)});
    }
    for (Eigen::Index i = 0; i < sphere.V.rows(); ++i) {
        labels[i] = std::min(kParts - 1, static_cast<int>((sphere.V(i, 0) + 1) / 2 * kParts));
    }
    chain.weights = weights_from_labels(labels, kParts);
    SubspaceMetric metric = quasi_articulated_metric(sphere, chain);
    metric.update(sphere);
    const std::vector<FieldBlock> blocks = metric.orthonormal_blocks();
    Eigen::Index columns = 0;
    for (const FieldBlock& block : blocks) {
        columns += block.fields.cols();
    }
    EXPECT_EQ(columns, 7 + 3 * (kParts - 1));  // the rigid motions and three turns per joint
    Eigen::MatrixXd Q(3 * sphere.V.rows(), columns);
    Eigen::Index column = 0;
    for (const FieldBlock& block : blocks) {
        Q.middleCols(column, block.fields.cols()) = block.fields;
        column += block.fields.cols();
    }
    Eigen::MatrixXd MQ = Q;
    for (Eigen::Index i = 0; i < sphere.V.rows(); ++i) {
        MQ.middleRows(3 * i, 3) *= metric.masses()[i];
    }
    EXPECT_LT((Q.transpose() * MQ - Eigen::MatrixXd::Identity(columns, columns)).norm(), 1e-9);
    const VertexField U = test::noisy_icosphere(3, 0.3, 4).V;
    EXPECT_LT(test::relative_error(metric.gradient(metric.apply(U)), U), 1e-10);
    EXPECT_LT(test::relative_error(metric.apply(metric.gradient(U)), U), 1e-10);
}

// Noise at every vertex with its part-motion components taken out: QᵀD = 0 for the fields Q
// of `metric`'s blocks (QᵀMQ = I, M the lumped masses), so that no part motion explains it.
VertexField noise_no_part_motion_explains(const SubspaceMetric& metric, unsigned seed) {
    const Eigen::Index n = metric.masses().size();
    Eigen::VectorXd d = test::random_matrix(3 * n, 1, seed);  // vertex i at rows 3i..3i+2
    for (const FieldBlock& block : metric.orthonormal_blocks()) {
        Eigen::MatrixXd MQ = block.fields;
        for (Eigen::Index i = 0; i < n; ++i) {
            MQ.middleRows(3 * i, 3) *= metric.masses()[i];
        }
        d -= MQ * (block.fields.transpose() * d);
    }
    VertexField D(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
        D.row(i) = d.segment<3>(3 * i).transpose();
    }
    return D;
}

// With smoothing_length the residual is measured in H1: the part of a rough differential that
// no part motion explains moves smoothly, and the bend stays cheap.
TEST(QuasiArticulatedMetric, SmoothsTheResidualOverAnH1Base) {
    const TriangleMesh arm = make_limb(3);
    const PartModel parts = test::two_part_arm(arm);
    SubspaceMetric plain = quasi_articulated_metric(arm, parts);
    SubspaceMetric smooth = quasi_articulated_metric(arm, parts, {.smoothing_length = 3});
    plain.update(arm);
    smooth.update(arm);
    const VertexField U = test::noisy_icosphere(3, 0.3, 4).V.topRows(arm.V.rows());
    EXPECT_LT(test::relative_error(smooth.gradient(smooth.apply(U)), U), 1e-9);
    EXPECT_GT((U.array() * smooth.apply(U).array()).sum(), 0);

    // A rough differential (noise at every vertex that no part motion explains, whose gradient
    // is the residual's alone): its gradient's Dirichlet energy per unit M-norm, with and
    // without the smoothing. Over 30 draws the ratio is 0.023–0.049. (Plain noise lets the part
    // motions' own share in, which no smoothing changes: 0.008–0.12.)
    const Eigen::SparseMatrix<double> K = cotan_stiffness(arm);
    const auto roughness = [&](const VertexField& v) {
        const VertexField Mv = (v.array().colwise() * plain.masses().array()).matrix();
        return (v.array() * (K * v).array()).sum() / (v.array() * Mv.array()).sum();
    };
    const VertexField rough = noise_no_part_motion_explains(plain, 1);
    const double plain_roughness = roughness(plain.gradient(rough));
    const double smooth_roughness = roughness(smooth.gradient(rough));
    EXPECT_LT(smooth_roughness, 0.1 * plain_roughness)
        << smooth_roughness << " " << plain_roughness;

    // The bend about the joint still costs a small multiple of its B-norm (measured 0.11: the
    // test's ramp is not quite the blended weights, and that rest costs in full).
    VertexField bend(arm.V.rows(), 3);
    for (Eigen::Index i = 0; i < arm.V.rows(); ++i) {
        const Eigen::Vector3d x = arm.V.row(i).transpose();
        const double lower = std::clamp((x.x() - 0.8) / 0.4, 0.0, 1.0);
        bend.row(i) = lower * Eigen::Vector3d::UnitZ().cross(x - Eigen::Vector3d(1, 0, 0));
    }
    H1Metric h1(SobolevOptions{.lambda = std::pow(3 * mean_edge_length(arm), 2)});
    h1.update(arm);
    EXPECT_LT((bend.array() * smooth.apply(bend).array()).sum(),
              0.2 * (bend.array() * h1.apply(bend).array()).sum());
    EXPECT_THROW((void)quasi_articulated_metric(arm, parts, {.smoothing_length = -1}),
                 InvalidInput);
}

}  // namespace
}  // namespace genflow
