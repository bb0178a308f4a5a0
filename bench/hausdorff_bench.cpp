// SPDX-License-Identifier: MIT
// Pseudo-Hausdorff energy + gradient on the TOSCA cat pair of $GENFLOW_DATA (28K-vertex
// template or ground-truth target against the 21K-vertex remeshed target), truncated and full;
// and on the pair simplified to the size of a match's coarsest level (cat: 505 and 370 vertices,
// truncation 1e-2 as match() uses), where a match makes most of its evaluations (12.6K of the
// cat's 13.3K), and, with descriptors, at about 1,000 vertices each (a FAUST_r match's coarsest
// level).
// Without the data it uses two generated spheres of similar sizes.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/io/read_mesh.h"
#include "genflow/matching/multiresolution.h"
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

// The three meshes simplified to about the sizes of the cat match's coarsest level (471 and 361
// vertices; match() simplifies each level from the one before, this goes straight there).
const CatPair& coarse_cat() {
    static const CatPair pair = [] {
        return CatPair{genflow::coarsen(cat().template_mesh, 471).mesh,
                       genflow::coarsen(cat().aligned, 471).mesh,
                       genflow::coarsen(cat().target, 361).mesh};
    }();
    return pair;
}

void run(benchmark::State& state, const genflow::TriangleMesh& moving,
         const genflow::TriangleMesh& target, double truncation,
         const genflow::PointDescriptors& descriptors = {}) {
    const double epsilon = genflow::mean_edge_length(target);
    const genflow::PseudoHausdorffEnergy energy(
        target, {.alpha = 8, .epsilon = epsilon, .truncation = truncation}, descriptors);
    std::size_t pairs = 0;
    for (auto _ : state) {
        const auto evaluation = energy.evaluate(moving);
        benchmark::DoNotOptimize(evaluation.differential.data());
        pairs = evaluation.pairs;
    }
    state.counters["pairs"] = static_cast<double>(pairs);
    state.counters["P"] = static_cast<double>(moving.V.rows());
    state.counters["Q"] = static_cast<double>(target.V.rows());
}

void BM_PseudoHausdorffAligned(benchmark::State& state) {
    run(state, cat().aligned, cat().target, 1e-4);
}
void BM_PseudoHausdorffUnaligned(benchmark::State& state) {
    run(state, cat().template_mesh, cat().target, 1e-4);
}
void BM_PseudoHausdorffAlignedFull(benchmark::State& state) {
    run(state, cat().aligned, cat().target, 0);
}
void BM_PseudoHausdorffCoarseAligned(benchmark::State& state) {
    run(state, coarse_cat().aligned, coarse_cat().target, 1e-2);
}
// With descriptors, as the guided flows of a match's coarsest level: here each point's own
// position scaled by 0.1, three columns that set the points apart as signatures do.
void BM_PseudoHausdorffCoarseGuided(benchmark::State& state) {
    const CatPair& pair = coarse_cat();
    run(state, pair.aligned, pair.target, 1e-2,
        genflow::PointDescriptors{0.1 * pair.aligned.V, 0.1 * pair.target.V});
}

// The same at the size of a FAUST_r match's coarsest level (about 1,000 vertices each), whose
// descriptor tables (8 MB each) no longer fit the core's own caches.
void BM_PseudoHausdorffThousandGuided(benchmark::State& state) {
    static const CatPair pair = [] {
        return CatPair{{},
                       genflow::coarsen(cat().aligned, 1000).mesh,
                       genflow::coarsen(cat().target, 1000).mesh};
    }();
    run(state, pair.aligned, pair.target, 1e-2,
        genflow::PointDescriptors{0.1 * pair.aligned.V, 0.1 * pair.target.V});
}

}  // namespace

BENCHMARK(BM_PseudoHausdorffAligned)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PseudoHausdorffUnaligned)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_PseudoHausdorffAlignedFull)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_PseudoHausdorffCoarseAligned)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PseudoHausdorffCoarseGuided)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PseudoHausdorffThousandGuided)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
