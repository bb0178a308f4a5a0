// SPDX-License-Identifier: MIT
// match() of a complete template onto a real single-view range scan of the same object: the
// Stanford bunny's reconstruction ($GENFLOW_DATA/smoothing/stanford_bunny.ply) onto its raw
// scan bun000 (bun000_rangescan.ply, scanner noise, open boundary, 4 components), which is
// in the reconstruction's frame. The right match moves the template by no more than the noise.
// Skips without the data.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "genflow/io/read_mesh.h"
#include "genflow/matching/correspondence.h"
#include "genflow/matching/match.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/spatial/closest_point.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// Found partial by its boundary, the scan is matched one-sided from the start that faces it:
// where the scan shows the bunny (template vertices within 1 % of the diagonal of it), the
// template moves by 1.0 % of the diagonal (sliding along the surface included), against 4.6 %
// matched as a whole, whose unseen side folds onto the scan (10.9 % over all vertices).
TEST(RangeScanMatch, BunnyScanMovesTheTemplateLittleWhereItShowsIt) {
    const auto data = test::data_directory();
    if (!data || !std::filesystem::exists(*data / "smoothing" / "bun000_rangescan.ply")) {
        GTEST_SKIP() << "no data directory (set GENFLOW_DATA)";
    }
    const TriangleMesh bunny = read_mesh(*data / "smoothing" / "stanford_bunny.ply");
    const TriangleMesh scan = read_mesh(*data / "smoothing" / "bun000_rangescan.ply");
    const MatchResult result = match(bunny, scan);
    const double diagonal = bounding_box_diagonal(scan);
    const Eigen::MatrixX3d on_scan = positions_of(closest_points(bunny.V, scan));
    double moved = 0;
    int seen = 0;
    for (Eigen::Index i = 0; i < bunny.V.rows(); ++i) {
        if ((on_scan.row(i) - bunny.V.row(i)).norm() < 0.01 * diagonal) {
            moved += (result.deformed.V.row(i) - bunny.V.row(i)).norm();
            ++seen;
        }
    }
    moved /= seen * diagonal;
    std::printf("bunny onto bun000: %d template vertices seen, moved by %.2f %% of the diagonal\n",
                seen, 100 * moved);
    EXPECT_TRUE(result.partial_target);
    EXPECT_GT(seen, bunny.V.rows() / 3);
    EXPECT_LT(moved, 0.02);
}

}  // namespace
}  // namespace genflow
