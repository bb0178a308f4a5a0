// SPDX-License-Identifier: MIT
#include "matching/turned_parts.h"

#include <gtest/gtest.h>

#include <numbers>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"

namespace genflow {
namespace {

// The generated limb with its +x end turned 162° about the limb's axis in its own place, as a
// match can leave a hand palm for back. (Whether a functional map sees such a turn depends on
// the shape: on this limb, nearly round about its axis, 60 eigenfunctions do not; on TOSCA
// michael's hands they do, RealPairs.FullBodyKeepsItsHeadOnStraight.)
struct TurnedEnd {
    static constexpr double kTurnAt = 1.2;
    static constexpr double kWidth = 0.3;
    TriangleMesh rest = make_limb(4);
    Eigen::MatrixX3d deformed =
        bend_at_joints(rest.V, {Joint{.centre = Eigen::Vector3d(kTurnAt, 0, 0),
                                      .direction = Eigen::Vector3d::UnitX(),
                                      .axis = Eigen::Vector3d::UnitX(),
                                      .angle = 0.9 * std::numbers::pi,
                                      .width = kWidth}});
};

// Mean distance between two placements over the vertices whose rest x is in [from, to).
double mean_distance(const TurnedEnd& limb, const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b,
                     double from, double to) {
    double sum = 0;
    int count = 0;
    for (Eigen::Index i = 0; i < limb.rest.V.rows(); ++i) {
        if (limb.rest.V(i, 0) >= from && limb.rest.V(i, 0) < to) {
            sum += (a.row(i) - b.row(i)).norm();
            ++count;
        }
    }
    return sum / count;
}

// A part as find_turned_parts() reports it, the map putting every vertex at rest: the part
// turns back exactly, its region by the share of the turn that brings each vertex nearest to
// the map's place, and nothing else moves.
TEST(TurnedParts, TurnsThePartBackAndBlendsItsRegion) {
    const TurnedEnd limb;
    detail::TurnedPart part;
    for (Eigen::Index i = 0; i < limb.rest.V.rows(); ++i) {
        const double x = limb.rest.V(i, 0);
        if (x >= TurnedEnd::kTurnAt + TurnedEnd::kWidth) {
            part.vertices.push_back(i);
        } else if (x >= 0) {
            part.region.push_back(i);
        }
    }
    part.region_mapped = limb.rest.V(part.region, Eigen::all);
    part.from_centre = limb.deformed(part.vertices, Eigen::all).colwise().mean();
    part.to_centre = limb.rest.V(part.vertices, Eigen::all).colwise().mean();
    part.turn = Eigen::AngleAxisd(0.9 * std::numbers::pi, -Eigen::Vector3d::UnitX());

    const Eigen::MatrixX3d turned = detail::turned_back(limb.rest, limb.deformed, {part});
    for (const Eigen::Index v : part.vertices) {
        EXPECT_LT((turned.row(v) - limb.rest.V.row(v)).norm(), 1e-12) << "vertex " << v;
    }
    const double lo = TurnedEnd::kTurnAt - TurnedEnd::kWidth;
    const double hi = TurnedEnd::kTurnAt + TurnedEnd::kWidth;
    const double blend_before = mean_distance(limb, limb.deformed, limb.rest.V, lo, hi);
    const double blend_after = mean_distance(limb, turned, limb.rest.V, lo, hi);
    EXPECT_LT(blend_after, 0.5 * blend_before) << blend_before << " -> " << blend_after;
    for (Eigen::Index i = 0; i < limb.rest.V.rows(); ++i) {
        if (limb.rest.V(i, 0) < 0) {
            ASSERT_EQ(turned.row(i), limb.deformed.row(i)) << "vertex " << i;
        }
    }
}

// A perfect match of a mesh onto itself: the map (ZoomOut from the identity) disputes nothing.
TEST(TurnedParts, FindsNothingInAPerfectMatch) {
    const TurnedEnd limb;
    const detail::FineSpectrum spectrum(limb.rest, limb.rest);
    const detail::VertexMap map = spectrum.zoomed_out_map(limb.rest.V);
    EXPECT_EQ(map.functions, 60);
    const Eigen::MatrixX3d mapped = limb.rest.V(map.target_vertex, Eigen::all);
    EXPECT_LT(mean_distance(limb, mapped, limb.rest.V, -10, 10),
              0.005 * bounding_box_diagonal(limb.rest));
    EXPECT_TRUE(detail::find_turned_parts(limb.rest, limb.rest.V, limb.rest, map).empty());
    EXPECT_THROW(
        (void)detail::find_turned_parts(limb.rest, limb.rest.V.topRows(10), limb.rest, map),
        InvalidInput);
    EXPECT_THROW((void)spectrum.zoomed_out_map(limb.rest.V.topRows(10)), InvalidInput);
}

}  // namespace
}  // namespace genflow
