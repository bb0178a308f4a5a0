// SPDX-License-Identifier: MIT
#include "genflow/matching/spectral_map.h"

#include <gtest/gtest.h>

#include "genflow/exceptions.h"
#include "genflow/operators/mesh_size.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// The figure's template against its posed, resampled, turned and scaled target: the map puts
// each template vertex near where it belongs, and not on its mirror image, which preserves the
// descriptors as well.
TEST(SpectralMap, MapsThePosedFigureWithoutMirroringIt) {
    const test::PosedSpikedFigure figure;
    const SpectralMap map = spectral_map(figure.template_mesh, figure.target);
    ASSERT_EQ(map.target_vertex.size(), static_cast<std::size_t>(figure.template_mesh.V.rows()));
    EXPECT_LT(figure.mean_distance(figure.target.V(map.target_vertex, Eigen::all)), 0.03);
    EXPECT_LT(map.orientation_ratio, 1);  // measured on the coarsened target (2000 vertices)
    EXPECT_LT(orientation_ratio(figure.template_mesh, figure.target, map.target_vertex), 1);

    // The same map after the template's own reflection: about as far from the truth as the
    // figure is wide, and the ratio says it reverses the orientation.
    std::vector<Eigen::Index> mirrored;
    for (const Eigen::Index v : test::figure_mirror(figure.template_mesh)) {
        mirrored.push_back(map.target_vertex[static_cast<std::size_t>(v)]);
    }
    EXPECT_GT(figure.mean_distance(figure.target.V(mirrored, Eigen::all)), 0.1);
    EXPECT_GT(orientation_ratio(figure.template_mesh, figure.target, mirrored), 1);
}

TEST(SpectralMap, RefusesBadOptionsAndMaps) {
    const TriangleMesh figure = test::spiked_figure(2, 0);
    SpectralMapOptions options;
    options.basis_sizes = {};
    EXPECT_THROW((void)spectral_map(figure, figure, options), InvalidInput);
    options = {};
    options.signed_bands = {5, 100};
    EXPECT_THROW((void)spectral_map(figure, figure, options), InvalidInput);
    EXPECT_THROW((void)orientation_ratio(figure, figure, {0, 1}), InvalidInput);
    const MapOrientation orientation(figure, figure);
    EXPECT_THROW((void)orientation.ratio({0, 1}), InvalidInput);
    std::vector<Eigen::Index> outside(static_cast<std::size_t>(figure.V.rows()), 0);
    outside.back() = figure.V.rows();
    EXPECT_THROW((void)orientation.ratio(outside), InvalidInput);
}

// MapOrientation computes the spectra once and scores each map as orientation_ratio() does.
TEST(MapOrientation, ScoresEachMapAsOrientationRatioDoes) {
    const test::PosedSpikedFigure figure;
    const SpectralMap map = spectral_map(figure.template_mesh, figure.target);
    std::vector<Eigen::Index> mirrored;
    for (const Eigen::Index v : test::figure_mirror(figure.template_mesh)) {
        mirrored.push_back(map.target_vertex[static_cast<std::size_t>(v)]);
    }
    const MapOrientation orientation(figure.template_mesh, figure.target);
    for (const std::vector<Eigen::Index>& vertices : {map.target_vertex, mirrored}) {
        EXPECT_EQ(orientation.ratio(vertices),
                  orientation_ratio(figure.template_mesh, figure.target, vertices));
    }
    EXPECT_LT(orientation.ratio(map.target_vertex), 1);
    EXPECT_GT(orientation.ratio(mirrored), 1);
}

}  // namespace
}  // namespace genflow
