// SPDX-License-Identifier: MIT
// Exact surface distances between a generated noisy torus of N vertices and its simplification
// to a tenth (as bench/anchors compares with CGAL on the armadillo): the Hausdorff distances
// alone and with the mean and RMS quadrature, for the cost curve against N; and the
// closest-point queries they are made of.
#include <benchmark/benchmark.h>

#include <map>
#include <vector>

#include "cost_curve.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/spatial/closest_point.h"
#include "genflow/spatial/surface_distance.h"

namespace {

struct DistancePair {
    genflow::TriangleMesh fine;
    genflow::TriangleMesh coarse;
};

// A noisy torus of about `vertices` vertices (5 % of its edge length) and its simplification
// to a tenth.
const DistancePair& pair_of(int vertices) {
    static std::map<int, DistancePair> made;
    auto found = made.find(vertices);
    if (found == made.end()) {
        DistancePair pair;
        pair.fine = genflow::bench::noisy_torus_of_size(vertices, 0.05);
        pair.coarse = genflow::coarsen(pair.fine, vertices / 10).mesh;
        found = made.emplace(vertices, std::move(pair)).first;
    }
    return found->second;
}

void distances(benchmark::State& state, bool mean_and_rms) {
    const DistancePair& pair = pair_of(static_cast<int>(state.range(0)));
    for (auto _ : state) {
        const genflow::SurfaceDistances d =
            genflow::surface_distances(pair.fine, pair.coarse, {.mean_and_rms = mean_and_rms});
        benchmark::DoNotOptimize(d.hausdorff);
    }
    state.counters["V"] = static_cast<double>(pair.fine.V.rows());
}

void BM_ExactHausdorff(benchmark::State& state) {
    distances(state, false);
}
void BM_SurfaceDistancesWithMean(benchmark::State& state) {
    distances(state, true);
}

// Closest-point queries at the midpoints of the coarse mesh's edges against the fine mesh, as
// the Hausdorff search makes them.
void BM_BvhClosestPoint(benchmark::State& state) {
    const DistancePair& pair = pair_of(static_cast<int>(state.range(0)));
    const genflow::TriangleBvh bvh(pair.fine);
    std::vector<Eigen::Vector3d> midpoints;
    for (Eigen::Index f = 0; f < pair.coarse.F.rows(); ++f) {
        midpoints.push_back(
            0.5 * (pair.coarse.V.row(pair.coarse.F(f, 0)) + pair.coarse.V.row(pair.coarse.F(f, 1)))
                      .transpose());
    }
    for (auto _ : state) {
        for (const Eigen::Vector3d& p : midpoints) {
            benchmark::DoNotOptimize(bvh.closest_point(p).distance);
        }
    }
    state.counters["queries"] = static_cast<double>(midpoints.size());
}

}  // namespace

BENCHMARK(BM_ExactHausdorff)
    ->Apply(genflow::bench::cost_curve_sizes)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SurfaceDistancesWithMean)
    ->ArgName("V")
    ->Arg(10'000)
    ->Arg(50'000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhClosestPoint)->ArgName("V")->Arg(50'000)->Unit(benchmark::kMillisecond);
