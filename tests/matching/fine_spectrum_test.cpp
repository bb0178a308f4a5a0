// SPDX-License-Identifier: MIT
#include "matching/fine_spectrum.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <numbers>

#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"
#include "matching/functional_map.h"

namespace genflow {
namespace {

// The limb (about 6 long), its +x end bent by 90° at x = 1, as the template placed right and as
// a target sampled anew.
struct BentLimb {
    TriangleMesh rest = make_limb(4);
    TriangleMesh target = bent(make_limb(4, 7));
    Eigen::MatrixX3d placed = bent(rest).V;

    static TriangleMesh bent(TriangleMesh mesh) {
        mesh.V = bend_at_joints(mesh.V, {Joint{.centre = Eigen::Vector3d(1, 0, 0),
                                               .direction = Eigen::Vector3d::UnitX(),
                                               .axis = Eigen::Vector3d::UnitZ(),
                                               .angle = std::numbers::pi / 2,
                                               .width = 0.3}});
        return mesh;
    }

    // The right placement slid along the limb by 0.3 in its rest frame (a few faces).
    [[nodiscard]] Eigen::MatrixX3d slid() const {
        TriangleMesh moved = rest;
        moved.V.col(0).array() += 0.3;
        return bent(moved).V;
    }

    // Mean distance of a placement of the template from the right one.
    [[nodiscard]] double error(const Eigen::MatrixX3d& placement) const {
        return (placement - placed).rowwise().norm().mean();
    }
};

// ZoomOut from a placement slid along the limb (by 0.3 in its rest frame, a few faces) puts
// the vertices back near where they belong: the map follows the shape's intrinsic geometry, not
// the nearest surface.
TEST(FineSpectrum, MapFromASlidPlacementPutsTheVerticesBack) {
    const BentLimb limb;
    const detail::FineSpectrum spectrum(limb.rest, limb.target);
    const Eigen::MatrixX3d slid_placement = limb.slid();
    const detail::VertexMap map = spectrum.zoomed_out_map(slid_placement);
    EXPECT_EQ(map.functions, 60);
    EXPECT_EQ(map.target_vertex.size(), static_cast<std::size_t>(limb.rest.V.rows()));
    const double before = limb.error(slid_placement);
    const double after = limb.error(limb.target.V(map.target_vertex, Eigen::all));
    std::printf("mean distance from the right placement: slid %.4f, mapped %.4f\n", before, after);
    EXPECT_LT(after, 0.5 * before);
    EXPECT_LT(after, 0.025 * bounding_box_diagonal(limb.target));
}

// One map from each of kFineMapFirstSizes, in that order, each as zoomed_out_map() finds it
// from that size, and each putting the slid vertices back.
TEST(FineSpectrum, MapsFromEachFirstSize) {
    const BentLimb limb;
    const detail::FineSpectrum spectrum(limb.rest, limb.target);
    const Eigen::MatrixX3d slid_placement = limb.slid();
    const std::vector<detail::VertexMap> maps = spectrum.zoomed_out_maps(slid_placement);
    ASSERT_EQ(maps.size(), detail::kFineMapFirstSizes.size());
    for (std::size_t k = 0; k < maps.size(); ++k) {
        const detail::VertexMap alone =
            spectrum.zoomed_out_map(slid_placement, detail::kFineMapFirstSizes[k]);
        EXPECT_EQ(maps[k].target_vertex, alone.target_vertex) << "size " << k;
        EXPECT_LT(limb.error(limb.target.V(maps[k].target_vertex, Eigen::all)),
                  0.5 * limb.error(slid_placement))
            << "size " << k;
    }
}

TEST(FineSpectrum, RefusesAPlacementOfAnotherSizeAndNoFirstFunction) {
    const BentLimb limb;
    const detail::FineSpectrum spectrum(limb.rest, limb.target);
    EXPECT_THROW((void)spectrum.zoomed_out_map(limb.placed.topRows(10)), InvalidInput);
    EXPECT_THROW((void)spectrum.zoomed_out_map(limb.placed, 0), InvalidInput);
}

// Rows of small integers make every distance exact, so that ties are real: the nearest row is
// the first of the closest, as a scan finds it. 2100 rows and 300 columns cross the tiles
// nearest_rows() works in.
TEST(FunctionalMap, NearestRowsAreTheFirstClosest) {
    std::srand(7);
    const auto small_integers = [](Eigen::Index rows) {
        return Eigen::MatrixXd(Eigen::MatrixXd::NullaryExpr(
            rows, 4, [] { return static_cast<double>(std::rand() % 7 - 3); }));
    };
    const Eigen::MatrixXd from = small_integers(2100);
    const Eigen::MatrixXd to = small_integers(300);
    const std::vector<Eigen::Index> nearest = detail::nearest_rows(from, to);
    ASSERT_EQ(nearest.size(), 2100U);
    int ties = 0;
    for (Eigen::Index i = 0; i < from.rows(); ++i) {
        Eigen::Index first_closest = 0;
        double closest = (from.row(i) - to.row(0)).squaredNorm();
        for (Eigen::Index j = 1; j < to.rows(); ++j) {
            const double d = (from.row(i) - to.row(j)).squaredNorm();
            ties += d == closest ? 1 : 0;
            if (d < closest) {
                closest = d;
                first_closest = j;
            }
        }
        EXPECT_EQ(nearest[static_cast<std::size_t>(i)], first_closest) << i;
    }
    EXPECT_GT(ties, 100);  // the tie rule was tested
}

}  // namespace
}  // namespace genflow
