// SPDX-License-Identifier: MIT
#include "matching/intrinsic_start.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// The template at rest, and the target: the figure posed, sampled otherwise, turned, scaled
// and moved; `truth` is where each template vertex belongs on it.
struct PosedFigure {
    Similarity motion{
        .rotation =
            Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix(),
        .translation = Eigen::Vector3d(4, -1, 2),
        .scale = 2.5};
    TriangleMesh template_mesh = test::spiked_figure(3, 0);
    TriangleMesh target;
    Eigen::MatrixX3d truth;

    PosedFigure() {
        target = test::spiked_figure(4, 7);
        target.V = motion.apply(test::pose_spiked_figure(target.V));
        truth = motion.apply(test::pose_spiked_figure(template_mesh.V));
    }

    [[nodiscard]] double mean_distance(const Eigen::MatrixX3d& placement) const {
        return (placement - truth).rowwise().norm().mean() / bounding_box_diagonal(target);
    }
};

TEST(IntrinsicStart, PlacesAPosedFigureWhereItBelongs) {
    const PosedFigure figure;
    const std::optional<detail::IntrinsicStart> start =
        detail::intrinsic_start(figure.template_mesh, figure.target);
    ASSERT_TRUE(start.has_value());
    EXPECT_GE(start->landmarks, 4);  // the legs' tips bent away from each other: 4 of 5 agree
    EXPECT_GT(start->orientation, 0.5);
    // 3.4 % (without the turning functions, 6.3 %: parts of the map follow the reflection).
    EXPECT_LT(figure.mean_distance(start->placement), 0.045);
    // The similarity recovers the motion: the sphere in the middle lands on its place.
    const Eigen::MatrixX3d placed = start->similarity.apply(figure.template_mesh.V);
    double core = 0;
    int count = 0;
    for (Eigen::Index i = 0; i < placed.rows(); ++i) {
        if (figure.template_mesh.V.row(i).norm() < 1.05) {
            core += (placed.row(i) - figure.truth.row(i)).norm();
            ++count;
        }
    }
    EXPECT_LT(core / count / bounding_box_diagonal(figure.target), 0.05);
    EXPECT_NEAR(start->similarity.scale, figure.motion.scale, 0.1 * figure.motion.scale);
}

}  // namespace
}  // namespace genflow
