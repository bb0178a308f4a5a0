// SPDX-License-Identifier: MIT
// The exact surface distance and the truncated pseudo-Hausdorff energy on real pairs of
// $GENFLOW_DATA: each against a reference computed without its speed-ups.
#include <gtest/gtest.h>

#include <string>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/io/read_mesh.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/spatial/surface_distance.h"
#include "support/reference_distances.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

using test::sampled_distance;
using test::SampledDistance;

TEST(SurfaceDistance, AgreesWithDenseSamplingOnARealPairWithinTheStatedBounds) {
    const auto data = test::data_directory();
    if (!data) {
        GTEST_SKIP() << "no data directory (set GENFLOW_DATA)";
    }
    // The small pairs of pairs.json: template against ground-truth target.
    for (const char* pair :
         {"faust_000_001_small", "tosca_cat_0_4_small", "tosca_centaur_0_5_small"}) {
        const TriangleMesh A =
            read_mesh(*data / "matching/small" / (std::string(pair) + "_template.ply"));
        const TriangleMesh B =
            read_mesh(*data / "matching/small" / (std::string(pair) + "_target.ply"));
        const SurfaceDistances d = surface_distances(A, B);
        const SampledDistance s = sampled_distance(A, B, 4);
        // sampled ≤ true ≤ reported upper bound, and true ≤ sampled + radius (1-Lipschitz).
        EXPECT_LE(s.max, d.a_to_b.hausdorff_upper_bound + 1e-12) << pair;
        EXPECT_LE(d.a_to_b.hausdorff, s.max + s.radius) << pair;
        EXPECT_NEAR(d.a_to_b.mean, s.mean, d.a_to_b.mean_error_bound + s.radius) << pair;
        EXPECT_GT(d.a_to_b.mean, 0) << pair;
    }
}

TEST(PseudoHausdorff, TruncatedAgreesWithFullSumsOnARealPair) {
    const auto data = test::data_directory();
    if (!data) {
        GTEST_SKIP() << "no data directory (set GENFLOW_DATA)";
    }
    // The end of a matching: the same surface in two samplings (ground truth vs remeshed).
    const TriangleMesh X = read_mesh(*data / "matching/small/tosca_cat_0_4_small_target.ply");
    const TriangleMesh Y =
        read_mesh(*data / "matching/small/tosca_cat_0_4_small_target_remeshed.ply");
    const double epsilon = mean_edge_length(Y);
    const PseudoHausdorffEnergy exact(Y, {.alpha = 8, .epsilon = epsilon, .truncation = 0});
    const PseudoHausdorffEnergy truncated(Y, {.alpha = 8, .epsilon = epsilon, .truncation = 1e-4});
    const auto e = exact.evaluate(X);
    const auto t = truncated.evaluate(X);
    EXPECT_LE(std::abs(t.value - e.value) / (e.value + epsilon), 1e-4 / (16 * (1 - 1e-4)));
    EXPECT_LT(test::relative_error(t.differential, e.differential), 1e-3);
    EXPECT_LT(static_cast<double>(t.pairs), 0.2 * static_cast<double>(e.pairs));
}

}  // namespace
}  // namespace genflow
