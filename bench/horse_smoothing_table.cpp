// SPDX-License-Identifier: MIT
// Prints the smoothing table of docs/benchmarks.md: each method on
// $GENFLOW_DATA/smoothing/horse_noisy.ply, RMS vertex distance to horse.ply (same connectivity)
// after every step, in units of the mean edge length h, and the volume change. Usage:
// horse_smoothing_table [DT] [STEPS]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "genflow/io/read_mesh.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/volume.h"
#include "genflow/smoothing/smoothing.h"

int main(int argc, char** argv) {
    const char* data = std::getenv("GENFLOW_DATA");
    const std::filesystem::path directory =
        std::filesystem::path(data != nullptr ? data : "../shared/data") / "smoothing";
    if (!std::filesystem::exists(directory / "horse.ply")) {
        std::fprintf(stderr, "horse_smoothing_table: %s/horse.ply not found (set GENFLOW_DATA)\n",
                     directory.string().c_str());
        return 2;
    }
    const double dt = argc > 1 ? std::atof(argv[1]) : 0.5;
    const int steps = argc > 2 ? std::atoi(argv[2]) : 6;
    const genflow::TriangleMesh clean = genflow::read_mesh(directory / "horse.ply");
    const genflow::TriangleMesh noisy = genflow::read_mesh(directory / "horse_noisy.ply");
    const double h = genflow::mean_edge_length(noisy);
    const double volume = genflow::enclosed_volume(noisy);
    const auto rms = [&](const genflow::TriangleMesh& mesh) {
        return std::sqrt((mesh.V - clean.V).rowwise().squaredNorm().mean()) / h;
    };
    std::printf("horse_noisy vs horse: %ld vertices, h = %.4g, dt = %g h², start RMS = %.3f h\n\n",
                static_cast<long>(noisy.V.rows()), h, dt, rms(noisy));
    std::printf(
        "| method | best step | RMS / h at best | volume change at best | after %d steps: RMS / h, "
        "volume | s/step |\n",
        steps);
    std::printf("|---|---:|---:|---:|---:|---:|\n");
    struct Method {
        const char* name;
        genflow::FlowResult (*run)(const genflow::TriangleMesh&, const genflow::SmoothingOptions&);
        double volume_lambda;
    };
    for (const Method& method :
         {Method{"mcf (L2, explicit)", genflow::mean_curvature_flow, 1},
          Method{"fairing (H1)", genflow::implicit_fairing, 1},
          Method{"fairing2 (H2, μ = h⁴)", genflow::higher_order_fairing, 1},
          Method{"volume-fairing λ = 0.05", genflow::volume_controlled_fairing, 0.05},
          Method{"volume-fairing λ = 0.01", genflow::volume_controlled_fairing, 0.01}}) {
        int best_step = 0;
        double best = rms(noisy);
        double best_volume = 0;
        double last_rms = best;
        double last_volume = 0;
        genflow::SmoothingOptions options{
            .time_step = dt, .steps = steps, .volume_lambda = method.volume_lambda};
        options.progress = [&](const genflow::FlowProgress& progress) {
            last_rms = rms(*progress.mesh);
            last_volume = 100 * (genflow::enclosed_volume(*progress.mesh) - volume) / volume;
            if (last_rms < best) {
                best = last_rms;
                best_step = progress.step;
                best_volume = last_volume;
            }
            return true;
        };
        const genflow::FlowResult result = method.run(noisy, options);
        std::printf("| %s | %d | %.3f | %+.3f%% | %.3f, %+.3f%% | %.2f |\n", method.name, best_step,
                    best, best_volume, last_rms, last_volume,
                    result.seconds / std::max(1, result.steps));
    }
    return 0;
}
