// SPDX-License-Identifier: MIT
#include "genflow/mesh/validate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

TriangleMesh two_triangles() {
    TriangleMesh mesh;
    mesh.V.resize(4, 3);
    mesh.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
    mesh.F.resize(2, 3);
    mesh.F << 0, 1, 2, 0, 2, 3;
    return mesh;
}

bool mentions(const ValidationReport& report, const std::string& text) {
    for (const auto& issue : report.issues) {
        if (issue.message.find(text) != std::string::npos) {
            return true;
        }
    }
    return false;
}

TEST(Validate, CleanClosedMeshHasNoIssues) {
    const ValidationReport report = validate(make_icosphere(2));
    EXPECT_TRUE(report.ok());
    EXPECT_TRUE(report.issues.empty());
    EXPECT_TRUE(report.closed());
    EXPECT_TRUE(report.manifold());
    EXPECT_EQ(report.components, 1);
    EXPECT_EQ(report.euler_characteristic, 2);
    EXPECT_FALSE(report.inward_oriented);
}

TEST(Validate, EmptyMeshesAreErrors) {
    EXPECT_FALSE(validate(TriangleMesh{}).ok());
    TriangleMesh no_faces = two_triangles();
    no_faces.F.resize(0, 3);
    const ValidationReport report = validate(no_faces);
    EXPECT_FALSE(report.ok());
    EXPECT_EQ(report.first_error(), "mesh has no faces");
}

TEST(Validate, NonFiniteCoordinatesAreErrors) {
    TriangleMesh mesh = two_triangles();
    mesh.V(2, 1) = std::numeric_limits<double>::quiet_NaN();
    mesh.V(3, 0) = std::numeric_limits<double>::infinity();
    const ValidationReport report = validate(mesh);
    EXPECT_FALSE(report.ok());
    EXPECT_EQ(report.non_finite_vertices, 2);
    EXPECT_EQ(report.first_error(), "2 vertices with non-finite coordinates (first: vertex 2)");
}

// Coordinates so large that squared areas would overflow (1e308 made the area inf and the
// volume's sign meaningless) are refused, as non-finite ones are.
TEST(Validate, CoordinatesBeyondTheLargestAreErrors) {
    TriangleMesh mesh = two_triangles();
    mesh.V(1, 2) = -1e308;
    mesh.V(3, 0) = 2 * kLargestCoordinate;
    const ValidationReport report = validate(mesh);
    EXPECT_FALSE(report.ok());
    EXPECT_EQ(report.huge_vertices, 2);
    EXPECT_EQ(report.first_error(), "2 vertices with a coordinate beyond ±1e50 (first: vertex 1)");
    EXPECT_TRUE(validate(TriangleMesh{kLargestCoordinate * two_triangles().V, mesh.F}).ok());
}

// A mesh whose every face has zero area has no surface to measure, smooth or match: an error
// that names the file at once, where the algorithms failed later with a message of their own.
TEST(Validate, AMeshWithoutAreaIsAnError) {
    TriangleMesh flat = two_triangles();
    flat.V.col(1).setZero();
    const ValidationReport report = validate(flat);
    EXPECT_FALSE(report.ok());
    EXPECT_EQ(report.first_error(), "every face has zero area");
    TriangleMesh one_flat = two_triangles();
    one_flat.V(3, 0) = 1;  // face 1 flat, face 0 not
    one_flat.V(3, 1) = 1;
    EXPECT_TRUE(validate(one_flat).ok());
}

TEST(Validate, OutOfRangeIndicesAreErrors) {
    TriangleMesh mesh = two_triangles();
    mesh.F(1, 2) = 4;
    ValidationReport report = validate(mesh);
    EXPECT_FALSE(report.ok());
    EXPECT_EQ(report.out_of_range_faces, 1);
    mesh.F(1, 2) = -3;
    report = validate(mesh);
    EXPECT_EQ(report.out_of_range_faces, 1);
    EXPECT_EQ(report.first_error(), "1 faces with vertex indices out of range (first: face 1)");
}

TEST(Validate, DegenerateRepeatedAndDuplicateFacesAreWarnings) {
    TriangleMesh mesh = two_triangles();
    mesh.V.conservativeResize(6, 3);
    mesh.V.row(4) << 2, 0, 0;
    mesh.V.row(5) << 3, 0, 0;  // 1, 4, 5 are collinear
    mesh.F.conservativeResize(6, 3);
    mesh.F.row(2) << 1, 4, 5;  // zero area
    mesh.F.row(3) << 1, 1, 2;  // repeated index
    mesh.F.row(4) << 2, 0, 1;  // duplicate of face 0, rotated
    mesh.F.row(5) << 0, 2, 3;  // duplicate of face 1
    const ValidationReport report = validate(mesh);
    EXPECT_TRUE(report.ok());
    EXPECT_EQ(report.zero_area_faces, 1);
    EXPECT_EQ(report.repeated_index_faces, 1);
    EXPECT_EQ(report.duplicate_faces, 2);
    EXPECT_TRUE(mentions(report, "2 duplicate faces (first: face"));
}

TEST(Validate, SliversAreWarnings) {
    TriangleMesh mesh = two_triangles();
    mesh.V(2, 1) = 1e-3;  // angle at vertex 0 of face 0 is 0.06°
    mesh.V(3, 1) = 1e-3;
    const ValidationReport report = validate(mesh);
    EXPECT_EQ(report.sliver_faces, 2);
    EXPECT_EQ(report.zero_area_faces, 0);
}

// A face is a sliver when its smallest angle is below the limit, however close to it: the apex
// angle θ of an isosceles triangle (legs 1, θ < 60° the smallest) on either side of the limit,
// by a millionth (decided by the test's products) and by 1e-12 (by atan2).
TEST(Validate, SliversAreFacesWhoseSmallestAngleIsBelowTheLimit) {
    const auto slivers = [](double apex_degrees, double limit_degrees) {
        const double apex = apex_degrees * std::numbers::pi / 180;
        TriangleMesh mesh;
        mesh.V.resize(3, 3);
        mesh.V << 0, 0, 0, 1, 0, 0, std::cos(apex), std::sin(apex), 0;
        mesh.F.resize(1, 3);
        mesh.F << 0, 1, 2;
        return validate(mesh, {.sliver_angle_degrees = limit_degrees}).sliver_faces;
    };
    for (const double limit : {0.5, 1.0, 10.0, 45.0}) {
        for (const double off : {1e-6, 1e-12}) {
            EXPECT_EQ(slivers(limit * (1 - off), limit), 1) << limit << " " << off;
            EXPECT_EQ(slivers(limit * (1 + off), limit), 0) << limit << " " << off;
        }
    }
    // From 60° on every triangle is a sliver: its smallest angle is at most 60°.
    EXPECT_EQ(slivers(60, 75), 1);
    EXPECT_EQ(slivers(30, 0), 0);
}

TEST(Validate, NonManifoldEdge) {
    TriangleMesh mesh = two_triangles();
    mesh.V.conservativeResize(5, 3);
    mesh.V.row(4) << 0.5, 0.5, 1;
    mesh.F.conservativeResize(3, 3);
    mesh.F.row(2) << 0, 2, 4;  // a third face on edge 0-2
    const ValidationReport report = validate(mesh);
    EXPECT_EQ(report.non_manifold_edges, 1);
    EXPECT_FALSE(report.manifold());
    EXPECT_FALSE(report.genus.has_value());
    EXPECT_TRUE(mentions(report, "1 non-manifold edges (first: edge 0-2)"));
}

TEST(Validate, NonManifoldVertexWhereTwoConesTouch) {
    // Two triangles that share only vertex 0 (a bow tie).
    TriangleMesh mesh;
    mesh.V.resize(5, 3);
    mesh.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0;
    mesh.F.resize(2, 3);
    mesh.F << 0, 1, 2, 0, 3, 4;
    const ValidationReport report = validate(mesh);
    EXPECT_EQ(report.non_manifold_vertices, 1);
    EXPECT_EQ(report.non_manifold_edges, 0);
    EXPECT_EQ(report.components, 1);
    EXPECT_TRUE(mentions(report, "(first: vertex 0)"));
}

TEST(Validate, InconsistentOrientation) {
    TriangleMesh mesh = two_triangles();
    mesh.F.row(1) << 0, 3, 2;  // runs edge 0-2 the same way as face 0
    const ValidationReport report = validate(mesh);
    EXPECT_EQ(report.inconsistent_orientation_edges, 1);
    EXPECT_FALSE(report.genus.has_value());
}

TEST(Validate, InwardFacesOnAClosedMesh) {
    TriangleMesh mesh = make_icosphere(1);
    mesh.F.col(1).swap(mesh.F.col(2));
    const ValidationReport report = validate(mesh);
    EXPECT_TRUE(report.inward_oriented);
    EXPECT_TRUE(mentions(report, "faces point inward"));
}

TEST(Validate, BoundaryLoopsComponentsAndUnreferencedVertices) {
    TriangleMesh mesh = make_grid(3);
    const Eigen::Index n = mesh.V.rows();
    TriangleMesh second = make_grid(2);
    mesh.V.conservativeResize(n + second.V.rows() + 1, 3);
    mesh.V.bottomRows(second.V.rows() + 1).setZero();
    mesh.V.block(n, 0, second.V.rows(), 3) = second.V.rowwise() + Eigen::RowVector3d(5, 0, 0);
    mesh.F.conservativeResize(mesh.F.rows() + second.F.rows(), 3);
    mesh.F.bottomRows(second.F.rows()) = second.F.array() + static_cast<int>(n);
    const ValidationReport report = validate(mesh);
    EXPECT_EQ(report.components, 2);
    EXPECT_EQ(report.boundary_loops, 2);
    EXPECT_EQ(report.unreferenced_vertices, 1);
    EXPECT_EQ(report.genus, 0);
    EXPECT_TRUE(report.ok());
}

TEST(Validate, GenusOfATorusWithAHole) {
    TriangleMesh mesh = make_torus(12, 6);
    mesh.F.conservativeResize(mesh.F.rows() - 1, 3);  // remove one face: one boundary loop
    const ValidationReport report = validate(mesh);
    EXPECT_EQ(report.boundary_loops, 1);
    EXPECT_EQ(report.genus, 1);
}

}  // namespace
}  // namespace genflow
