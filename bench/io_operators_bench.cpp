// SPDX-License-Identifier: MIT
// Loading and operator assembly on a 50K-vertex mesh (a noisy 250×200 torus, generated, so the
// benchmark needs no data). Run through bench/run_benchmarks.sh for a table.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

#include "genflow/io/read_mesh.h"
#include "genflow/io/write_mesh.h"
#include "genflow/mesh/primitives.h"
#include "genflow/mesh/validate.h"
#include "genflow/operators/area.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/laplacian_eigenbasis.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/normals.h"
#include "genflow/operators/volume.h"

namespace {

const genflow::TriangleMesh& mesh_50k() {
    static const genflow::TriangleMesh mesh = [] {
        genflow::TriangleMesh torus = genflow::make_torus(250, 200);
        return genflow::add_noise(torus, 0.05 * genflow::mean_edge_length(torus), 1);
    }();
    return mesh;
}

std::filesystem::path file_50k(const std::string& extension) {
    const auto path = std::filesystem::temp_directory_path() /
                      ("genflow-bench-" + std::to_string(::getpid()) + "." + extension);
    if (!std::filesystem::exists(path)) {
        genflow::write_mesh(path, mesh_50k());
    }
    return path;
}

void read_format(benchmark::State& state, const std::string& extension) {
    const auto path = file_50k(extension);
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::read_mesh(path));
    }
    std::filesystem::remove(path);
}

void BM_ReadPlyBinary(benchmark::State& state) {
    read_format(state, "ply");
}
void BM_ReadObj(benchmark::State& state) {
    read_format(state, "obj");
}
void BM_ReadOff(benchmark::State& state) {
    read_format(state, "off");
}

void BM_WritePlyBinary(benchmark::State& state) {
    const auto path = std::filesystem::temp_directory_path() / "genflow-bench-write.ply";
    for (auto _ : state) {
        genflow::write_mesh(path, mesh_50k());
    }
    std::filesystem::remove(path);
}

void BM_Validate(benchmark::State& state) {
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::validate(mesh_50k()));
    }
}

void BM_MeanEdgeLength(benchmark::State& state) {
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::mean_edge_length(mesh_50k()));
    }
}

void BM_CotanStiffness(benchmark::State& state) {
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::cotan_stiffness(mesh_50k()));
    }
}

void BM_MassMatrixFull(benchmark::State& state) {
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::mass_matrix(mesh_50k(), genflow::MassType::Full));
    }
}

void BM_LumpedMassVoronoi(benchmark::State& state) {
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::lumped_masses(mesh_50k(), genflow::MassType::Voronoi));
    }
}

void BM_VertexNormals(benchmark::State& state) {
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::vertex_normals(mesh_50k()));
    }
}

void BM_AreaGradient(benchmark::State& state) {
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::surface_area_gradient(mesh_50k()));
    }
}

void BM_VolumeGradient(benchmark::State& state) {
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::enclosed_volume_gradient(mesh_50k()));
    }
}

// The 60 lowest eigenpairs (the size of a functional map that resolves hands) by Lanczos on the
// 50K-vertex torus; the dense solve, for scale, on a 2000-vertex one.
void BM_LaplacianEigenbasisLowest60(benchmark::State& state) {
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::laplacian_eigenbasis(mesh_50k(), 60));
    }
}

void BM_LaplacianEigenbasisDense2K(benchmark::State& state) {
    const genflow::TriangleMesh torus = genflow::make_torus(50, 40);
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::laplacian_eigenbasis(torus));
    }
}

}  // namespace

BENCHMARK(BM_ReadPlyBinary)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadObj)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadOff)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WritePlyBinary)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Validate)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeanEdgeLength)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CotanStiffness)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MassMatrixFull)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LumpedMassVoronoi)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VertexNormals)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AreaGradient)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VolumeGradient)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
BENCHMARK(BM_LaplacianEigenbasisLowest60)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_LaplacianEigenbasisDense2K)->Unit(benchmark::kMillisecond)->Iterations(1);
