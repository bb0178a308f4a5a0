// SPDX-License-Identifier: MIT
#include "genflow/operators/hole_area.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "genflow/exceptions.h"
#include "genflow/mesh/edges.h"
#include "genflow/mesh/face_selection.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/area.h"

namespace genflow {
namespace {

// `mesh` without the faces whose centroid `drop` is true for.
template <typename Drop>
TriangleMesh without(const TriangleMesh& mesh, Drop drop) {
    return {mesh.V, faces_where(mesh.F, [&](Eigen::Index f) {
                return !drop((mesh.V.row(mesh.F(f, 0)) + mesh.V.row(mesh.F(f, 1)) +
                              mesh.V.row(mesh.F(f, 2))) /
                             3);
            })};
}

TEST(HoleArea, ClosedSurfaceHasNone) {
    EXPECT_EQ(hole_area(make_icosphere(3)), 0);
    EXPECT_THROW((void)hole_area(TriangleMesh{Eigen::MatrixX3d::Zero(2, 3),
                                              Eigen::MatrixX3i::Constant(1, 3, 5)}),
                 InvalidInput);
}

// A flat sheet's loops are planar, so the estimate is exact: the outer square closes with the
// sheet's own area 1, and a square hole of 0.4 × 0.4 cells adds its area.
TEST(HoleArea, PlanarLoopsCloseWithTheirExactArea) {
    const TriangleMesh grid = make_grid(10);
    EXPECT_NEAR(hole_area(grid), 1, 1e-12);
    const TriangleMesh holed = without(grid, [](const Eigen::RowVector3d& c) {
        return std::abs(c.x() - 0.5) < 0.2 && std::abs(c.y() - 0.5) < 0.2;
    });
    EXPECT_NEAR(hole_area(holed), 1 + 0.16, 1e-12);
}

// A hole that meets the rim at corners (the faces of the first row that touch the rim at a
// vertex only, and the cells above them) is a loop of its own: its area adds to the rim's,
// exactly as on a flat sheet, instead of cancelling against it (the two loops run opposite
// ways about the sheet's normal).
TEST(HoleArea, HoleTouchingTheRimAddsItsArea) {
    const TriangleMesh grid = make_grid(10);
    const TriangleMesh notched = without(grid, [](const Eigen::RowVector3d& c) {
        return c.y() > 0.05 && c.y() < 0.3 && c.x() > 0.1 && c.x() < 0.4;
    });
    const Eigen::MatrixX2i rim = boundary_edges(grid.F);
    const Eigen::MatrixX2i edges = boundary_edges(notched.F);
    for (Eigen::Index e = 0; e < rim.rows(); ++e) {  // the notch leaves the rim as it was
        EXPECT_TRUE(
            ((edges.col(0).array() == rim(e, 0)) && (edges.col(1).array() == rim(e, 1))).any())
            << e;
    }
    const double cut = surface_area(grid) - surface_area(notched);
    EXPECT_GT(cut, 0.05);
    EXPECT_NEAR(hole_area(notched), 1 + cut, 1e-12);
}

// A sphere's cap cut off leaves a circle of radius √(1 − h²): its disc, π (1 − h²), up to the
// polygon's chords. Two caps add up; moving, turning or scaling the sphere does not change it
// but by s².
TEST(HoleArea, CutCapsCloseWithTheirDiscs) {
    const TriangleMesh sphere = make_icosphere(5);
    const double h = 0.6;
    const TriangleMesh one =
        without(sphere, [&](const Eigen::RowVector3d& c) { return c.z() > h; });
    EXPECT_NEAR(hole_area(one), M_PI * (1 - h * h), 0.03 * M_PI * (1 - h * h));
    const TriangleMesh two =
        without(sphere, [&](const Eigen::RowVector3d& c) { return std::abs(c.z()) > h; });
    EXPECT_NEAR(hole_area(two), 2 * hole_area(one), 0.02 * hole_area(one));
    TriangleMesh moved = one;
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    moved.V = ((3 * one.V) * turn.transpose()).rowwise() + Eigen::RowVector3d(100, -50, 20);
    EXPECT_NEAR(hole_area(moved), 9 * hole_area(one), 1e-9 * hole_area(moved));
}

// Faces along a hole's rim dropped in 20 teeth: the rim gets far longer, its area barely changes.
TEST(HoleArea, RaggedRimBarelyChangesIt) {
    const TriangleMesh sphere = make_icosphere(5);
    const TriangleMesh holed =
        without(sphere, [](const Eigen::RowVector3d& c) { return c.z() > 0.6; });
    const TriangleMesh ragged = without(sphere, [](const Eigen::RowVector3d& c) {
        return c.z() > 0.6 || (c.z() > 0.55 && std::sin(40 * std::atan2(c.y(), c.x())) > 0);
    });
    EXPECT_LT(ragged.F.rows(), holed.F.rows() - 100);
    EXPECT_GT(boundary_edges(ragged.F).rows(), 3 * boundary_edges(holed.F).rows() / 2);
    EXPECT_NEAR(hole_area(ragged), hole_area(holed), 0.1 * hole_area(holed));
}

}  // namespace
}  // namespace genflow
