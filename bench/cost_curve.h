// SPDX-License-Identifier: MIT
// What the cost curves of docs/benchmarks.md share: their sizes and their generated shape.
#pragma once

#include <benchmark/benchmark.h>

#include <cmath>

#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"

namespace genflow::bench {

/// A torus of about `vertices` vertices (rings : sides = 5 : 4), its vertices moved at random
/// by `noise` times its mean edge length (seed 1).
inline TriangleMesh noisy_torus_of_size(int vertices, double noise) {
    const int sides = static_cast<int>(std::lround(std::sqrt(0.8 * vertices)));
    const TriangleMesh torus =
        make_torus(static_cast<int>(std::lround(vertices / static_cast<double>(sides))), sides);
    return add_noise(torus, noise * mean_edge_length(torus), 1);
}

/// The vertex counts of a cost curve, 1K to 200K, as the benchmark's argument V.
inline void cost_curve_sizes(benchmark::internal::Benchmark* curve) {
    curve->ArgName("V")->Arg(1'000)->Arg(10'000)->Arg(50'000)->Arg(200'000);
}

}  // namespace genflow::bench
