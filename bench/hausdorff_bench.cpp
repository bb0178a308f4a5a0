// SPDX-License-Identifier: MIT
// Pseudo-Hausdorff energy + gradient on the TOSCA cat pair of $GENFLOW_DATA (28K-vertex
// template or ground-truth target against the 21K-vertex remeshed target), truncated and full.
// Without the data it uses two generated spheres of similar sizes.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/io/read_mesh.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"

namespace {

struct CatPair {
    genflow::TriangleMesh template_mesh;  // cat0: another pose, not aligned
    genflow::TriangleMesh aligned;        // cat4: the target's own surface, other sampling
    genflow::TriangleMesh target;         // cat4 remeshed
};

const CatPair& cat() {
    static const CatPair pair = [] {
        const char* data = std::getenv("GENFLOW_DATA");
        const std::filesystem::path root = data != nullptr ? data : "../shared/data";
        if (std::filesystem::exists(root / "matching/tosca/cat0.ply")) {
            return CatPair{
                genflow::read_mesh(root / "matching/tosca/cat0.ply"),
                genflow::read_mesh(root / "matching/tosca/cat4.ply"),
                genflow::read_mesh(root / "matching/remeshed/tosca_cat_0_4_target_remeshed.ply")};
        }
        genflow::TriangleMesh shifted = genflow::make_icosphere(6);
        shifted.V.col(0).array() += 0.3;
        return CatPair{shifted, genflow::make_icosphere(6), genflow::make_icosphere(5)};
    }();
    return pair;
}

void run(benchmark::State& state, const genflow::TriangleMesh& moving, double truncation) {
    const double epsilon = genflow::mean_edge_length(cat().target);
    const genflow::PseudoHausdorffEnergy energy(
        cat().target, {.alpha = 8, .epsilon = epsilon, .truncation = truncation});
    std::size_t pairs = 0;
    for (auto _ : state) {
        const auto evaluation = energy.evaluate(moving);
        benchmark::DoNotOptimize(evaluation.differential.data());
        pairs = evaluation.pairs;
    }
    state.counters["pairs"] = static_cast<double>(pairs);
    state.counters["P"] = static_cast<double>(moving.V.rows());
    state.counters["Q"] = static_cast<double>(cat().target.V.rows());
}

void BM_PseudoHausdorffAligned(benchmark::State& state) {
    run(state, cat().aligned, 1e-4);
}
void BM_PseudoHausdorffUnaligned(benchmark::State& state) {
    run(state, cat().template_mesh, 1e-4);
}
void BM_PseudoHausdorffAlignedFull(benchmark::State& state) {
    run(state, cat().aligned, 0);
}

}  // namespace

BENCHMARK(BM_PseudoHausdorffAligned)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PseudoHausdorffUnaligned)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_PseudoHausdorffAlignedFull)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
