// SPDX-License-Identifier: MIT
// Landmarks: the similarity they imply, their term in every flow, and a match they steer.
#include "genflow/matching/landmarks.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numeric>

#include "genflow/evaluation/reference_landmarks.h"
#include "genflow/exceptions.h"
#include "genflow/matching/match.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"
#include "support/match_options.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

std::vector<Landmark> landmarks_at_vertices(const Eigen::MatrixX3d& to,
                                            std::vector<Eigen::Index> vertices) {
    std::vector<Landmark> landmarks;
    for (const Eigen::Index v : vertices) {
        landmarks.push_back({v, to.row(v).transpose()});
    }
    return landmarks;
}

TEST(LandmarkSimilarity, RecoversASimilarityFromThreePointsAndNeedsThem) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.2);
    Similarity motion;
    motion.rotation = Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, -2, 0.5).normalized()).matrix();
    motion.translation = Eigen::Vector3d(3, -1, 2);
    motion.scale = 2.5;
    const Eigen::MatrixX3d moved = motion.apply(mesh.V);
    const std::optional<Similarity> fit =
        landmark_similarity(landmarks_at_vertices(moved, {0, 5, 17}), mesh.V);
    ASSERT_TRUE(fit);
    EXPECT_NEAR(fit->scale, 2.5, 1e-12);
    EXPECT_LT((fit->rotation - motion.rotation).norm(), 1e-12);
    EXPECT_LT((fit->translation - motion.translation).norm(), 1e-12);
    EXPECT_NEAR(landmark_mean_squared_distance(landmarks_at_vertices(moved, {0, 5, 17, 30}),
                                               fit->apply(mesh.V)),
                0, 1e-20);
    // Two points, or three on a line, leave a rotation about the line free.
    EXPECT_FALSE(landmark_similarity(landmarks_at_vertices(moved, {0, 5}), mesh.V));
    Eigen::MatrixX3d line = mesh.V;
    line.row(2) = 0.3 * line.row(0) + 0.7 * line.row(1);
    EXPECT_FALSE(landmark_similarity(landmarks_at_vertices(line, {0, 1, 2}), line));
}

TEST(LandmarkSimilarity, WeighsEachLandmarkAsThatManyCopiesOfIt) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.2);
    Similarity motion;
    motion.rotation = Eigen::AngleAxisd(1.0, Eigen::Vector3d(0, 1, 1).normalized()).matrix();
    motion.translation = Eigen::Vector3d(-1, 4, 0.5);
    motion.scale = 0.7;
    Eigen::MatrixX3d moved = motion.apply(mesh.V);
    moved.row(30) += Eigen::RowVector3d(0.5, -0.2, 0.3);  // one landmark that disagrees
    std::vector<Landmark> weighted = landmarks_at_vertices(moved, {0, 5, 17, 30});
    weighted[1].weight = 3;
    weighted[3].weight = 0.5;
    const std::vector<Landmark> copies = landmarks_at_vertices(moved, {0, 5, 5, 5, 17, 30});
    std::vector<Landmark> doubled = copies;  // 0.5 against 1 + 3 + 1 as 1 against 2 + 6 + 2
    for (Landmark& landmark : doubled) {
        landmark.weight = landmark.vertex == 30 ? 1 : 2;
    }
    const std::optional<Similarity> fit = landmark_similarity(weighted, mesh.V);
    const std::optional<Similarity> fit_to_doubled = landmark_similarity(doubled, mesh.V);
    const std::optional<Similarity> fit_to_copies = landmark_similarity(copies, mesh.V);
    ASSERT_TRUE(fit && fit_to_doubled && fit_to_copies);
    EXPECT_LT((fit->matrix() - fit_to_doubled->matrix()).norm(), 1e-12);
    // The disagreeing landmark at half weight pulls the fit less than at a whole one.
    EXPECT_GT((fit->matrix() - fit_to_copies->matrix()).norm(), 1e-3);
    EXPECT_LT((fit->matrix() - motion.matrix()).norm(),
              (fit_to_copies->matrix() - motion.matrix()).norm());
    EXPECT_LT(landmark_mean_squared_distance(weighted, fit->apply(mesh.V)),
              landmark_mean_squared_distance(weighted, fit_to_copies->apply(mesh.V)));
}

TEST(ReferenceLandmarks, SpreadOverTheTemplateAndPairTheReferencePoints) {
    const TriangleMesh from = make_limb(3);
    TriangleMesh to = from;
    to.V.col(0) *= 2;  // the target's reference point k is the template's, stretched
    std::vector<Eigen::Index> reference(static_cast<std::size_t>(from.V.rows()));
    std::iota(reference.begin(), reference.end(), 0);
    const std::vector<Landmark> landmarks = reference_landmarks(from, reference, to, reference, 4);
    ASSERT_EQ(landmarks.size(), 4U);
    EXPECT_EQ(landmarks[0].vertex, 0);  // from reference point 0, then the farthest from those
    double closest_pair = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < landmarks.size(); ++a) {
        EXPECT_EQ(landmarks[a].target_point, to.V.row(landmarks[a].vertex).transpose());
        for (std::size_t b = 0; b < a; ++b) {
            closest_pair = std::min(
                closest_pair,
                (from.V.row(landmarks[a].vertex) - from.V.row(landmarks[b].vertex)).norm());
        }
    }
    // Four farthest-point samples spread along the limb: no two within a fifth of its diagonal
    // (the first four vertices of make_limb() lie within a few edge lengths).
    EXPECT_GT(closest_pair, 0.2 * bounding_box_diagonal(from));
    EXPECT_THROW((void)reference_landmarks(from, reference, to, {0, 1}, 1), InvalidInput);
    EXPECT_THROW((void)reference_landmarks(from, {0, 1}, to, {0, 1}, 3), InvalidInput);
    EXPECT_THROW((void)reference_landmarks(from, {0, from.V.rows()}, to, {0, 1}, 1), InvalidInput);
}

// The posed spiked figure (every spike bent 60–100°, sampled otherwise, turned, scaled 2.5× and
// moved) from the rigid starts alone, without the intrinsic start's second opinion: the spikes
// settle on the wrong ones (32 % of the diagonal off; the second opinion's tests show it). Six
// landmarks on spike tips (the template's farthest-point samples, each given its true place)
// steer the starts and hold every flow: the match is right.
TEST(Match, LandmarksSteerAMatchTheRigidStartsMiss) {
    const test::PosedSpikedFigure figure;
    MatchOptions options = test::one_reading_options();
    options.second_opinion.enabled = false;
    std::vector<Eigen::Index> every(static_cast<std::size_t>(figure.template_mesh.V.rows()));
    std::iota(every.begin(), every.end(), 0);
    options.landmarks.points = reference_landmarks(
        figure.template_mesh, every, TriangleMesh{figure.truth, figure.template_mesh.F}, every, 6);
    const MatchResult with = match(figure.template_mesh, figure.target, options);
    EXPECT_LT(figure.mean_distance(with.deformed.V), 0.05);  // 0.018
    ASSERT_TRUE(with.landmark_distance);
    EXPECT_LT(*with.landmark_distance, 0.01);  // 0.0024
}

// The mean distance of `deformed` to `truth`, over the diagonal of `truth`.
double mean_error_over_diagonal(const Eigen::MatrixX3d& deformed, const Eigen::MatrixX3d& truth) {
    return (deformed - truth).rowwise().norm().mean() /
           (truth.colwise().maxCoeff() - truth.colwise().minCoeff()).norm();
}

// The paper's flow alone (no alignment, no guidance) over two levels, from a limb turned a
// quarter about the normal of its length: d_H alone settles the limb across the target's,
// where they overlap (35 % of the diagonal off); four landmarks hold their vertices on every
// level, coarse ones on the level's nearest vertex, and draw the whole limb onto its place.
TEST(Match, LandmarksHoldTheirVerticesOnEveryLevel) {
    const TriangleMesh limb = make_limb(3);
    Similarity turn;
    turn.rotation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
    const TriangleMesh target{turn.apply(limb.V), limb.F};
    MatchOptions options = paper_match_options();
    options.levels = 2;
    options.coarse_vertices = 100;
    const MatchResult without = match(limb, target, options);
    EXPECT_GT(mean_error_over_diagonal(without.deformed.V, target.V), 0.1);

    std::vector<Eigen::Index> every(static_cast<std::size_t>(limb.V.rows()));
    std::iota(every.begin(), every.end(), 0);
    options.landmarks.points = reference_landmarks(limb, every, target, every, 4);
    const MatchResult with = match(limb, target, options);
    ASSERT_EQ(with.levels.size(), 2U);
    ASSERT_TRUE(with.landmark_distance);
    EXPECT_LT(*with.landmark_distance, 0.005);  // 0.001
    // 0.35 → 0.08: what is left is the surface sliding along itself between four points, which
    // this preset's flow of d_H alone does not see.
    EXPECT_LT(mean_error_over_diagonal(with.deformed.V, target.V), 0.1);
}

TEST(Match, RefusesLandmarksItCannotPlace) {
    const TriangleMesh mesh = make_limb(2);
    MatchOptions options;
    options.landmarks.points = {{mesh.V.rows(), Eigen::Vector3d::Zero()}};
    EXPECT_THROW((void)match(mesh, mesh, options), InvalidInput);
    options.landmarks.points = {{0, Eigen::Vector3d(0, NAN, 0)}};
    EXPECT_THROW((void)match(mesh, mesh, options), InvalidInput);
    options.landmarks.points = {{0, Eigen::Vector3d::Zero(), 0}};
    EXPECT_THROW((void)match(mesh, mesh, options), InvalidInput);
    options.landmarks.points = {{0, Eigen::Vector3d::Zero()}};
    options.landmarks.weight = -1;
    EXPECT_THROW((void)match(mesh, mesh, options), InvalidInput);
}

}  // namespace
}  // namespace genflow
