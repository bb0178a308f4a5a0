// SPDX-License-Identifier: MIT
#include "genflow/evaluation/scan_defects.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "genflow/evaluation/single_view.h"
#include "genflow/exceptions.h"
#include "genflow/mesh/edges.h"
#include "genflow/mesh/primitives.h"
#include "genflow/mesh/repair.h"
#include "genflow/operators/area.h"
#include "genflow/operators/hole_area.h"
#include "genflow/operators/mesh_size.h"

namespace genflow {
namespace {

// Whether every face of `part` is a face of `whole` (the same three indices, in order).
bool faces_are_among(const TriangleMesh& part, const TriangleMesh& whole) {
    for (Eigen::Index f = 0; f < part.F.rows(); ++f) {
        bool found = false;
        for (Eigen::Index g = 0; g < whole.F.rows() && !found; ++g) {
            found = part.F.row(f) == whole.F.row(g);
        }
        if (!found) {
            return false;
        }
    }
    return true;
}

// Holes drop the faces of discs: the vertices stay in order, the area falls by about the discs'
// (π r² each on a unit sphere, less where two overlap) and the sphere gets a boundary.
TEST(ScanDefects, HolesDropDiscsOfFacesAndKeepTheVertices) {
    const TriangleMesh sphere = make_icosphere(4);
    const ScanDefects defects{.holes = 3, .hole_radius = 0.1};
    const TriangleMesh holed = with_scan_defects(sphere, defects, 5);
    EXPECT_EQ(holed.V, sphere.V);
    EXPECT_TRUE(faces_are_among(holed, sphere));
    const double radius = 0.1 * bounding_box_diagonal(sphere);
    const double lost = surface_area(sphere) - surface_area(holed);
    EXPECT_GT(lost, 0.5 * M_PI * radius * radius);
    EXPECT_LT(lost, 3 * 1.3 * M_PI * radius * radius);
    EXPECT_GT(boundary_edges(holed.F).rows(), 0);
    EXPECT_EQ(with_scan_defects(sphere, defects, 5).F, holed.F);
    const TriangleMesh other = with_scan_defects(sphere, defects, 6);
    EXPECT_TRUE(other.F.rows() != holed.F.rows() || other.F != holed.F);
    EXPECT_EQ(with_scan_defects(sphere, ScanDefects{}, 5).F, sphere.F);
}

// A ragged boundary drops only faces at the boundary, about half of them.
TEST(ScanDefects, RaggedBoundaryDropsAboutHalfTheFacesAtTheBoundary) {
    const TriangleMesh half = single_view(make_icosphere(4), Eigen::Vector3d(0, 0, -1));
    const std::vector<bool> on_boundary = boundary_vertices(half.F, half.V.rows());
    Eigen::Index at_boundary = 0;
    for (Eigen::Index f = 0; f < half.F.rows(); ++f) {
        at_boundary += on_boundary[static_cast<std::size_t>(half.F(f, 0))] ||
                       on_boundary[static_cast<std::size_t>(half.F(f, 1))] ||
                       on_boundary[static_cast<std::size_t>(half.F(f, 2))];
    }
    const TriangleMesh ragged = with_scan_defects(half, ScanDefects{.ragged_boundary = true}, 3);
    EXPECT_TRUE(faces_are_among(ragged, half));
    const auto dropped = static_cast<double>(half.F.rows() - ragged.F.rows());
    // Binomial(n, 1/2): within five standard deviations √n/2 of n/2.
    const auto n = static_cast<double>(at_boundary);
    EXPECT_NEAR(dropped, n / 2, 2.5 * std::sqrt(n));
    EXPECT_GT(n, 100);
}

// Fragments add components apart from the surface, each a copy of a disc moved off it; the
// mesh's own vertices and faces stay as they were.
TEST(ScanDefects, FragmentsAreLooseCopiesOfDiscsOffTheSurface) {
    const TriangleMesh sphere = make_icosphere(4);
    const TriangleMesh scan = with_scan_defects(sphere, ScanDefects{.fragments = 4}, 9);
    ASSERT_GT(scan.V.rows(), sphere.V.rows());
    EXPECT_EQ(scan.V.topRows(sphere.V.rows()), sphere.V);
    EXPECT_EQ(scan.F.topRows(sphere.F.rows()), sphere.F);
    const RepairedSurface kept = repair_surface(scan);
    EXPECT_EQ(kept.counts.components_left_out, 4);
    // Each fragment is a disc of radius 0.02 diagonals: its area about π r².
    const double radius = 0.02 * bounding_box_diagonal(sphere);
    const double added = surface_area(scan) - surface_area(sphere);
    EXPECT_GT(added, 4 * 0.5 * M_PI * radius * radius);
    EXPECT_LT(added, 4 * 1.5 * M_PI * radius * radius);
}

// The frame cuts the sphere by a plane: by Archimedes a cap of height 2s on the unit sphere has
// the share s of its area, and the faces the plane crosses go too. One rim is left, a circle.
TEST(ScanDefects, OutOfFrameCutsACapOfTheStatedShare) {
    const TriangleMesh sphere = make_icosphere(4);
    const double share = 0.2;
    const TriangleMesh cut = with_scan_defects(sphere, ScanDefects{.out_of_frame = share}, 4);
    EXPECT_EQ(cut.V, sphere.V);
    EXPECT_TRUE(faces_are_among(cut, sphere));
    const double lost = 1 - surface_area(cut) / surface_area(sphere);
    EXPECT_GT(lost, share);
    EXPECT_LT(lost, share + 0.03);
    // The rim follows a circle of radius √(1 − 0.6²) = 0.8 (zigzagging along the faces), which
    // closes with a disc of area π 0.8².
    EXPECT_NEAR(hole_area(cut), M_PI * 0.64, 0.1 * M_PI * 0.64);
    const TriangleMesh other = with_scan_defects(sphere, ScanDefects{.out_of_frame = share}, 5);
    EXPECT_TRUE(other.F.rows() != cut.F.rows() || other.F != cut.F);
}

// Noise moves every coordinate by a Gaussian of σ mean edge lengths.
TEST(ScanDefects, NoiseHasTheStatedSpread) {
    const TriangleMesh sphere = make_icosphere(4);
    const TriangleMesh noisy = with_scan_defects(sphere, ScanDefects{.noise = 0.5}, 2);
    ASSERT_EQ(noisy.F, sphere.F);
    const Eigen::MatrixX3d moved = noisy.V - sphere.V;
    const double sigma = std::sqrt(moved.squaredNorm() / static_cast<double>(moved.size()));
    EXPECT_NEAR(sigma, 0.5 * mean_edge_length(sphere), 0.05 * mean_edge_length(sphere));
    EXPECT_NEAR(moved.mean(), 0, 0.05 * mean_edge_length(sphere));
}

TEST(ScanDefects, RefusesNegativeOrNonFiniteDefects) {
    const TriangleMesh sphere = make_icosphere(1);
    EXPECT_THROW((void)with_scan_defects(sphere, ScanDefects{.holes = -1}, 0), InvalidInput);
    EXPECT_THROW((void)with_scan_defects(sphere, ScanDefects{.hole_radius = NAN}, 0), InvalidInput);
    EXPECT_THROW((void)with_scan_defects(sphere, ScanDefects{.noise = -1}, 0), InvalidInput);
    EXPECT_THROW((void)with_scan_defects(sphere, ScanDefects{.fragment_radius = INFINITY}, 0),
                 InvalidInput);
    EXPECT_THROW((void)with_scan_defects(sphere, ScanDefects{.out_of_frame = 1}, 0), InvalidInput);
    EXPECT_THROW((void)with_scan_defects(sphere, ScanDefects{.out_of_frame = NAN}, 0),
                 InvalidInput);
}

}  // namespace
}  // namespace genflow
