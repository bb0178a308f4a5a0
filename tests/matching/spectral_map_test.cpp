// SPDX-License-Identifier: MIT
#include "genflow/matching/spectral_map.h"

#include <gtest/gtest.h>

#include "genflow/exceptions.h"
#include "genflow/operators/mesh_size.h"
#include "spatial/point_index.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// Each vertex of the spiked figure at rest (symmetric across x = 0) with the vertex nearest to
// its mirror image: the figure's one isometry, which reverses its orientation.
std::vector<Eigen::Index> mirror_of(const TriangleMesh& figure) {
    Eigen::MatrixX3d mirrored = figure.V;
    mirrored.col(0) *= -1;
    const detail::PointIndex index(figure.V);
    std::vector<Eigen::Index> mirror;
    for (Eigen::Index v = 0; v < figure.V.rows(); ++v) {
        mirror.push_back(index.nearest(mirrored.row(v).transpose()).first);
    }
    return mirror;
}

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
    for (const Eigen::Index v : mirror_of(figure.template_mesh)) {
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
}

}  // namespace
}  // namespace genflow
