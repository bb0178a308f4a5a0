// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <memory>

#include "genflow/energies/enclosed_volume_energy.h"
#include "genflow/energies/surface_area_energy.h"
#include "genflow/energies/weighted_sum_energy.h"
#include "genflow/exceptions.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

void expect_differential_matches_finite_differences(const Energy& energy,
                                                    const TriangleMesh& mesh) {
    const VertexField fd = test::finite_difference_gradient(
        [&](const TriangleMesh& m) { return energy.value(m); }, mesh);
    EXPECT_LT(test::relative_error(energy.differential(mesh), fd), 1e-6);
}

TEST(Energies, DifferentialsMatchCentralFiniteDifferences) {
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.2);
    expect_differential_matches_finite_differences(SurfaceAreaEnergy{}, mesh);
    expect_differential_matches_finite_differences(EnclosedVolumeEnergy{}, mesh);
    const WeightedSumEnergy sum({{2.0, std::make_shared<SurfaceAreaEnergy>()},
                                 {-0.5, std::make_shared<EnclosedVolumeEnergy>()}});
    expect_differential_matches_finite_differences(sum, mesh);
    EXPECT_NEAR(sum.value(mesh),
                2 * SurfaceAreaEnergy{}.value(mesh) - 0.5 * EnclosedVolumeEnergy{}.value(mesh),
                1e-12);
}

TEST(Energies, AreaLinearizationReproducesTheDifferential) {
    const TriangleMesh mesh = test::noisy_torus(12, 6, 0.2);
    const SurfaceAreaEnergy area;
    const auto linearization = area.linearize(mesh);
    ASSERT_TRUE(linearization);
    EXPECT_LT(
        test::relative_error(linearization->A * mesh.V + linearization->B, area.differential(mesh)),
        1e-12);
}

TEST(Energies, WeightedSumLinearizesOnlyWithPositiveLinearizableTerms) {
    const TriangleMesh mesh = test::noisy_icosphere(1);
    const auto area = std::make_shared<SurfaceAreaEnergy>();
    const auto volume = std::make_shared<EnclosedVolumeEnergy>();
    const auto sum = WeightedSumEnergy({{3.0, area}, {0.0, volume}}).linearize(mesh);
    ASSERT_TRUE(sum);
    EXPECT_LT(test::relative_error(sum->A * mesh.V, 3.0 * area->differential(mesh)), 1e-12);
    EXPECT_FALSE(WeightedSumEnergy({{1.0, area}, {1.0, volume}}).linearize(mesh));
    EXPECT_FALSE(WeightedSumEnergy({{-1.0, area}}).linearize(mesh));
    EXPECT_FALSE(EnclosedVolumeEnergy{}.linearize(mesh));
    EXPECT_THROW(WeightedSumEnergy({{NAN, area}}), InvalidInput);
    EXPECT_THROW(WeightedSumEnergy({{1.0, nullptr}}), InvalidInput);
}

}  // namespace
}  // namespace genflow
