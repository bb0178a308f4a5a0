// SPDX-License-Identifier: MIT
#include "genflow/mesh/repair.h"

#include <gtest/gtest.h>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/mesh/validate.h"
#include "genflow/operators/area.h"
#include "matching/carried_back.h"

namespace genflow {
namespace {

// `mesh` with `faces` appended.
TriangleMesh with_faces(TriangleMesh mesh, const std::vector<Eigen::RowVector3i>& faces) {
    const Eigen::Index first = mesh.F.rows();
    mesh.F.conservativeResize(first + static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t i = 0; i < faces.size(); ++i) {
        mesh.F.row(first + static_cast<Eigen::Index>(i)) = faces[i];
    }
    return mesh;
}

// `mesh` with a vertex appended at `position`; returns its index.
int add_vertex(TriangleMesh& mesh, const Eigen::RowVector3d& position) {
    mesh.V.conservativeResize(mesh.V.rows() + 1, 3);
    mesh.V.row(mesh.V.rows() - 1) = position;
    return static_cast<int>(mesh.V.rows() - 1);
}

// A closed sphere with a fin: one more face on the edge F(0, 0)–F(0, 1), out to a new vertex.
TriangleMesh sphere_with_fin() {
    TriangleMesh mesh = make_icosphere(2);
    const int a = mesh.F(0, 0);
    const int b = mesh.F(0, 1);
    const int tip = add_vertex(mesh, 1.5 * (mesh.V.row(a) + mesh.V.row(b)));
    return with_faces(mesh, {{a, b, tip}});
}

void expect_one_manifold_component(const TriangleMesh& mesh) {
    const ValidationReport report = validate(mesh);
    EXPECT_TRUE(report.manifold());
    EXPECT_EQ(report.components, 1);
    EXPECT_EQ(report.duplicate_faces, 0);
}

TEST(RepairSurface, ManifoldConnectedMeshComesBackUnchanged) {
    const TriangleMesh sphere = make_icosphere(2);
    const RepairedSurface repaired = repair_surface(sphere);
    EXPECT_FALSE(repaired.changed());
    EXPECT_EQ(repaired.summary(), "");
    EXPECT_EQ(repaired.mesh.V, sphere.V);
    EXPECT_EQ(repaired.mesh.F, sphere.F);
    for (Eigen::Index v = 0; v < sphere.V.rows(); ++v) {
        EXPECT_EQ(repaired.source_vertex[static_cast<std::size_t>(v)], v);
        EXPECT_EQ(repaired.repaired_vertex[static_cast<std::size_t>(v)], v);
    }
}

TEST(RepairSurface, RemovesDuplicateFacesOfEitherOrientation) {
    const TriangleMesh sphere = make_icosphere(2);
    const Eigen::RowVector3i f0 = sphere.F.row(0);
    const Eigen::RowVector3i f1 = sphere.F.row(1);
    const TriangleMesh doubled =
        with_faces(sphere, {f0, {f1(0), f1(2), f1(1)}, {f0(1), f0(2), f0(0)}});
    EXPECT_EQ(validate(doubled).duplicate_faces, 3);
    const RepairedSurface repaired = repair_surface(doubled);
    EXPECT_EQ(repaired.counts.duplicate_faces, 3);
    EXPECT_TRUE(repaired.changed());
    EXPECT_EQ(repaired.mesh.F, sphere.F);  // the first copy kept, in order
    EXPECT_EQ(repaired.mesh.V, sphere.V);
    expect_one_manifold_component(repaired.mesh);
}

TEST(RepairSurface, DetachesAFinOnAnEdgeAndLeavesItOut) {
    const TriangleMesh fin = sphere_with_fin();
    ASSERT_EQ(validate(fin).non_manifold_edges, 1);
    const RepairedSurface repaired = repair_surface(fin);
    // The fin's two edge vertices are split off the sphere; the fin is then its own component.
    EXPECT_EQ(repaired.counts.vertices_split, 2);
    EXPECT_EQ(repaired.counts.components_left_out, 1);
    const TriangleMesh sphere = make_icosphere(2);
    const double fin_area = surface_area(fin) - surface_area(sphere);
    EXPECT_NEAR(repaired.counts.area_left_out, fin_area / surface_area(fin), 1e-12);
    EXPECT_EQ(repaired.mesh.F, sphere.F);
    EXPECT_EQ(repaired.mesh.V, sphere.V);
    EXPECT_EQ(repaired.repaired_vertex.back(), -1);  // the fin's tip
    expect_one_manifold_component(repaired.mesh);
    EXPECT_NE(repaired.summary().find("split non-manifold vertices: 2"), std::string::npos)
        << repaired.summary();
}

TEST(RepairSurface, WeldsASeamOfCoincidentVertices) {
    const TriangleMesh sphere = make_icosphere(2);
    // Every face on the side x > 0 gets its own copies of its corners: the sphere falls into
    // pieces along a seam, as a mesh written per texture chart does.
    TriangleMesh seamed = sphere;
    Eigen::Index copies = 0;
    for (Eigen::Index f = 0; f < seamed.F.rows(); ++f) {
        Eigen::RowVector3d centroid = Eigen::RowVector3d::Zero();
        for (int c = 0; c < 3; ++c) {
            centroid += sphere.V.row(sphere.F(f, c)) / 3;
        }
        if (centroid.x() > 0) {
            for (int c = 0; c < 3; ++c) {
                seamed.F(f, c) = add_vertex(seamed, sphere.V.row(sphere.F(f, c)));
                ++copies;
            }
        }
    }
    ASSERT_GT(validate(seamed).components, 1);
    const RepairedSurface repaired = repair_surface(seamed);
    EXPECT_EQ(repaired.counts.vertices_welded, copies);
    EXPECT_EQ(repaired.counts.components_left_out, 0);
    EXPECT_EQ(repaired.mesh.V, sphere.V);
    EXPECT_EQ(repaired.mesh.F, sphere.F);
    expect_one_manifold_component(repaired.mesh);
    EXPECT_TRUE(validate(repaired.mesh).closed());
    for (Eigen::Index v = 0; v < seamed.V.rows(); ++v) {
        const Eigen::Index carrier = repaired.repaired_vertex[static_cast<std::size_t>(v)];
        ASSERT_GE(carrier, 0);
        EXPECT_EQ(repaired.mesh.V.row(carrier), seamed.V.row(v));
    }
}

// Two spheres touching at one vertex: welded there, then split into one vertex per fan; the
// larger sphere is kept, and the smaller one follows the displacement of the kept vertex
// nearest to it.
TEST(RepairSurface, SplitsSpheresTouchingAtAVertexAndCarriesTheOtherBack) {
    const TriangleMesh big = make_icosphere(2);
    TriangleMesh small = make_icosphere(1, 0.5);
    const Eigen::Index top = 0;
    const Eigen::RowVector3d touch = big.V.row(top);
    for (Eigen::Index v = 0; v < small.V.rows(); ++v) {
        small.V.row(v) = (small.V.row(v) - small.V.row(0)) * -1.0 + touch;
    }
    small.V.row(0) = touch;  // exactly
    TriangleMesh both = big;
    both.V.conservativeResize(big.V.rows() + small.V.rows(), 3);
    both.V.bottomRows(small.V.rows()) = small.V;
    const Eigen::MatrixX3i shifted = small.F.array() + static_cast<int>(big.V.rows());
    both.F.conservativeResize(big.F.rows() + small.F.rows(), 3);
    both.F.bottomRows(small.F.rows()) = shifted;

    const RepairedSurface repaired = repair_surface(both);
    EXPECT_EQ(repaired.counts.vertices_welded, 1);
    EXPECT_EQ(repaired.counts.vertices_split, 1);
    EXPECT_EQ(repaired.counts.components_left_out, 1);
    EXPECT_NEAR(repaired.counts.area_left_out,
                surface_area(small) / (surface_area(big) + surface_area(small)), 1e-12);
    EXPECT_EQ(repaired.mesh.V, big.V);
    EXPECT_EQ(repaired.mesh.F, big.F);

    const Eigen::RowVector3d shift(0.25, -1, 2);
    const Eigen::MatrixX3d moved = repaired.mesh.V.rowwise() + shift;
    const Eigen::MatrixX3d carried = detail::carried_back(repaired, both.V, moved);
    ASSERT_EQ(carried.rows(), both.V.rows());
    EXPECT_LT(((carried - both.V).rowwise() - shift).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_THROW(static_cast<void>(detail::carried_back(repaired, both.V, both.V)), InvalidInput);
}

// Asked to, repair keeps every component (a partial scan's pieces): two separate spheres come
// back whole, and nothing is said to be left out.
TEST(RepairSurface, KeepsEveryComponentWhenAsked) {
    const TriangleMesh big = make_icosphere(2);
    TriangleMesh both = big;
    const TriangleMesh small = make_icosphere(1, 0.5);
    both.V.conservativeResize(big.V.rows() + small.V.rows(), 3);
    both.V.bottomRows(small.V.rows()) = small.V.rowwise() + Eigen::RowVector3d(3, 0, 0);
    const Eigen::MatrixX3i shifted = small.F.array() + static_cast<int>(big.V.rows());
    both.F.conservativeResize(big.F.rows() + small.F.rows(), 3);
    both.F.bottomRows(small.F.rows()) = shifted;
    const RepairedSurface kept = repair_surface(both, {.largest_component_only = false});
    EXPECT_FALSE(kept.changed());
    EXPECT_EQ(kept.mesh.V, both.V);
    EXPECT_EQ(kept.mesh.F, both.F);
    EXPECT_EQ(repair_surface(both).counts.components_left_out, 1);
}

TEST(RepairSurface, RefusesAMeshWithNoProperFace) {
    TriangleMesh flat;
    flat.V = Eigen::MatrixX3d::Identity(3, 3);
    flat.F.resize(2, 3);
    flat.F << 0, 0, 1, 1, 2, 2;
    EXPECT_THROW(static_cast<void>(repair_surface(flat)), InvalidInput);
    flat.F << 0, 1, 2, 0, 1, 3;  // index out of range
    EXPECT_THROW(static_cast<void>(repair_surface(flat)), InvalidInput);
}

}  // namespace
}  // namespace genflow
