// SPDX-License-Identifier: MIT
// Fairing on real data: the noisy Cyberware horse against the clean
// one (same connectivity, faces pointing inward). Volume-controlled fairing must reach an RMS
// error no worse than plain implicit fairing at its best step count while changing the volume
// by less than 0.5%.
#include <gtest/gtest.h>

#include <cmath>

#include "genflow/io/read_mesh.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/volume.h"
#include "genflow/smoothing/smoothing.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

struct Trace {
    std::vector<double> rms;            // per step, in units of h
    std::vector<double> volume_change;  // per step, fraction of |V|
};

Trace trace(const TriangleMesh& noisy, const TriangleMesh& clean,
            FlowResult (*method)(const TriangleMesh&, const SmoothingOptions&),
            SmoothingOptions options) {
    const double h = mean_edge_length(noisy);
    const double volume = enclosed_volume(noisy);
    Trace t;
    options.progress = [&](const FlowProgress& progress) {
        t.rms.push_back(std::sqrt((progress.mesh->V - clean.V).rowwise().squaredNorm().mean()) / h);
        t.volume_change.push_back(std::abs(enclosed_volume(*progress.mesh) - volume) /
                                  std::abs(volume));
        return true;
    };
    const FlowResult result = method(noisy, options);
    EXPECT_TRUE(result.ok()) << result.message;
    return t;
}

TEST(HorseFairing, VolumeControlledFairingMatchesFairingWithoutShrinking) {
    const auto data = test::data_directory();
    if (!data) {
        GTEST_SKIP() << "no data directory (set GENFLOW_DATA)";
    }
    const TriangleMesh clean = read_mesh(*data / "smoothing" / "horse.ply");
    const TriangleMesh noisy = read_mesh(*data / "smoothing" / "horse_noisy.ply");
    const SmoothingOptions options{.time_step = 0.5, .steps = 4, .volume_lambda = 0.05};
    const Trace plain = trace(noisy, clean, implicit_fairing, options);
    const Trace controlled = trace(noisy, clean, volume_controlled_fairing, options);
    const auto best = std::min_element(plain.rms.begin(), plain.rms.end()) - plain.rms.begin();
    const double best_rms = plain.rms[static_cast<std::size_t>(best)];
    bool reached = false;
    for (std::size_t k = 0; k < controlled.rms.size(); ++k) {
        EXPECT_LT(controlled.volume_change[k], 0.005) << "step " << k + 1;
        reached = reached || controlled.rms[k] <= best_rms;
    }
    EXPECT_TRUE(reached) << "plain fairing's best RMS " << best_rms << " h at step " << best + 1;
    // Plain fairing shrinks: its volume change at its best step is the comparison figure.
    EXPECT_GT(plain.volume_change[static_cast<std::size_t>(best)], 0.005);
}

}  // namespace
}  // namespace genflow
