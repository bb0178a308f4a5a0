// SPDX-License-Identifier: MIT
// Landmarks spread into a dense map of a partial target by their geodesic distances.
#include "matching/spread_landmarks.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>

#include "genflow/mesh/face_selection.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/area.h"
#include "spatial/farthest_points.h"

namespace genflow {
namespace {

// An ellipsoid of three different axes (so that no two of its points lie alike towards every
// landmark) and the part of it below z = 0.2 of its height, turned and moved: a view of it, whose
// vertex i is the ellipsoid's vertex i.
struct CutEllipsoid {
    TriangleMesh whole = make_ellipsoid(3, Eigen::Vector3d(1.0, 0.7, 0.45));
    TriangleMesh cut;
    Eigen::Matrix3d turn = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
    Eigen::RowVector3d shift{3, -1, 2};

    CutEllipsoid() {
        cut.F = faces_where(whole.F, [&](Eigen::Index f) {
            return (whole.V(whole.F(f, 0), 2) + whole.V(whole.F(f, 1), 2) +
                    whole.V(whole.F(f, 2), 2)) /
                       3 <
                   0.2 * 0.45;
        });
        cut.V = (whole.V * turn.transpose()).rowwise() + shift;
    }

    // `count` landmarks spread over the cut part, each template vertex at its own place.
    [[nodiscard]] std::vector<Landmark> landmarks(Eigen::Index count) const {
        const std::vector<bool> on_cut = vertices_on_faces(cut.F, cut.V.rows());
        Eigen::MatrixX3d far_away = whole.V;
        for (Eigen::Index i = 0; i < whole.V.rows(); ++i) {
            if (!on_cut[static_cast<std::size_t>(i)]) {
                far_away.row(i).setConstant(1e3);  // coincident: never taken before the rest
            }
        }
        Eigen::Index lowest = 0;
        whole.V.col(2).minCoeff(&lowest);
        std::vector<Landmark> result;
        for (const Eigen::Index v : detail::farthest_points(far_away, lowest, count)) {
            result.push_back({v, cut.V.row(v).transpose()});
        }
        return result;
    }
};

// Mean distance, on the whole ellipsoid at rest, from each spread landmark's template vertex to
// where its point truly belongs (the same vertex), over the landmarks' spacing.
double mean_misplacement(const CutEllipsoid& shape, const std::vector<Landmark>& spread,
                         std::size_t given) {
    const double spacing = std::sqrt(surface_area(shape.whole) / static_cast<double>(given));
    double sum = 0;
    for (std::size_t k = given; k < spread.size(); ++k) {
        Eigen::Index truth = 0;
        (shape.cut.V.rowwise() - spread[k].target_point.transpose())
            .rowwise()
            .squaredNorm()
            .minCoeff(&truth);
        sum += (shape.whole.V.row(spread[k].vertex) - shape.whole.V.row(truth)).norm();
    }
    return sum / static_cast<double>(spread.size() - given) / spacing;
}

TEST(SpreadLandmarks, MapAViewOntoTheShapeItWasCutFrom) {
    const CutEllipsoid shape;
    const std::vector<Landmark> given = shape.landmarks(12);
    const std::vector<Landmark> spread =
        detail::spread_landmarks(shape.whole, shape.cut, given, 200);
    ASSERT_EQ(spread.size(), given.size() + 200);
    for (std::size_t k = 0; k < given.size(); ++k) {
        EXPECT_EQ(spread[k].vertex, given[k].vertex);
    }
    const double misplaced = mean_misplacement(shape, spread, given.size());
    std::printf("spread landmarks misplaced by %.3f of the landmarks' spacing on average\n",
                misplaced);
    EXPECT_LT(misplaced, 0.15);
}

// The target's vertex of each spread landmark (its point is one), with the template vertex it
// was given.
std::map<Eigen::Index, Eigen::Index> spread_map(const CutEllipsoid& shape,
                                                const std::vector<Landmark>& spread) {
    std::map<Eigen::Index, Eigen::Index> map;
    for (const Landmark& landmark : spread) {
        Eigen::Index point = 0;
        (shape.cut.V.rowwise() - landmark.target_point.transpose())
            .rowwise()
            .squaredNorm()
            .minCoeff(&point);
        map[point] = landmark.vertex;
    }
    return map;
}

TEST(SpreadLandmarks, DoNotDependOnWhereTheTargetIs) {
    const CutEllipsoid moved;
    CutEllipsoid in_place;
    in_place.cut.V = in_place.whole.V;
    const auto map_of = [](const CutEllipsoid& shape) {
        return spread_map(
            shape, detail::spread_landmarks(shape.whole, shape.cut, shape.landmarks(12), 100));
    };
    const std::map<Eigen::Index, Eigen::Index> a = map_of(moved);
    const std::map<Eigen::Index, Eigen::Index> b = map_of(in_place);
    int shared = 0;  // the samples may differ where the ellipsoid's symmetry ties distances
    for (const auto& [point, vertex] : a) {
        if (const auto found = b.find(point); found != b.end()) {
            EXPECT_EQ(found->second, vertex) << "target vertex " << point;
            ++shared;
        }
    }
    EXPECT_GE(shared, 30);
}

TEST(SpreadLandmarks, LeaveFewerThanThreeLandmarksAsTheyAre) {
    const CutEllipsoid shape;
    const std::vector<Landmark> two = shape.landmarks(2);
    EXPECT_EQ(detail::spread_landmarks(shape.whole, shape.cut, two, 100).size(), 2U);
    const std::vector<Landmark> three = shape.landmarks(3);
    EXPECT_EQ(detail::spread_landmarks(shape.whole, shape.cut, three, 100).size(), 103U);
}

}  // namespace
}  // namespace genflow
