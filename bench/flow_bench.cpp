// SPDX-License-Identifier: MIT
// Time per implicit-fairing step on the 48K-vertex horse ($GENFLOW_DATA/smoothing/horse_noisy.ply,
// or a generated 50K-vertex torus without the data): the first step (symbolic analysis +
// factorization + solve) and later steps separately (also in the smoothing flows' two halves,
// with the differential computed after the update or alongside it), through the library (whichever
// backend it was built with) and with CHOLMOD and Eigen's SimplicialLDLT side by side; one H1 step
// at the size of a match's coarsest level. Also the rebuild of the quasi-articulated metric
// (docs/formulas.md §6) at every flow step, on a generated 41K-vertex sphere cut into a chain of 17
// parts.
#include <benchmark/benchmark.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#ifdef GENFLOW_BENCH_HAS_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include "cost_curve.h"
#include "genflow/energies/surface_area_energy.h"
#include "genflow/io/read_mesh.h"
#include "genflow/mesh/primitives.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/metrics/volume_controlled_metric.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/parts/quasi_articulated_metric.h"
#include "genflow/smoothing/smoothing.h"

namespace {

const genflow::TriangleMesh& horse() {
    static const genflow::TriangleMesh mesh = [] {
        const char* data = std::getenv("GENFLOW_DATA");
        const std::filesystem::path path =
            std::filesystem::path(data != nullptr ? data : "../shared/data") / "smoothing" /
            "horse_noisy.ply";
        if (std::filesystem::exists(path)) {
            return genflow::read_mesh(path);
        }
        const genflow::TriangleMesh torus = genflow::make_torus(250, 200);
        return genflow::add_noise(torus, 0.3 * genflow::mean_edge_length(torus), 1);
    }();
    return mesh;
}

double dt() {
    const double h = genflow::mean_edge_length(horse());
    return 0.5 * h * h;
}

// One implicit-fairing step through the library: update (assemble + factor) and gradient.
void BM_FairingStepFirst(benchmark::State& state) {
    const genflow::SurfaceAreaEnergy area;
    for (auto _ : state) {
        genflow::H1Metric metric({.lambda = dt()});  // fresh: pays the symbolic analysis
        metric.update(horse());
        benchmark::DoNotOptimize(metric.gradient(area.differential(horse())));
    }
    state.counters["vertices"] = static_cast<double>(horse().V.rows());
}

void BM_FairingStepLater(benchmark::State& state) {
    const genflow::SurfaceAreaEnergy area;
    genflow::H1Metric metric({.lambda = dt()});
    metric.update(horse());
    for (auto _ : state) {
        metric.update(horse());  // same pattern: numeric factorization only
        benchmark::DoNotOptimize(metric.gradient(area.differential(horse())));
    }
}

// A later step of the smoothing flows' factorization (in two halves, wide supernodes) with the
// area's differential computed after the update (argument 0) or alongside the factorization, on
// the thread the lighter half leaves idle (1; Metric::update_alongside(), as the fairing flows
// take their steps).
void BM_FairingStepLaterInHalves(benchmark::State& state) {
    const genflow::SurfaceAreaEnergy area;
    genflow::H1Metric metric(
        {.lambda = dt(), .factorization = genflow::Factorization::ByFlopDensityWide});
    metric.update(horse());
    Eigen::MatrixX3d differential;
    const auto take_differential = [&] { differential = area.differential(horse()); };
    for (auto _ : state) {
        if (state.range(0) == 0) {
            metric.update(horse());
            take_differential();
        } else {
            metric.update_alongside(horse(), take_differential);
        }
        benchmark::DoNotOptimize(metric.gradient(differential));
    }
}

void BM_FairingAssembleOnly(benchmark::State& state) {
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::mass_matrix(horse(), genflow::MassType::Barycentric) +
                                 dt() * genflow::cotan_stiffness(horse()));
    }
}

// The cost curve of smoothing: five implicit-fairing steps through the library (set-up, five
// assemblies and factorizations, the solves) on a noisy torus of about V vertices.
void BM_FairingFiveStepsCurve(benchmark::State& state) {
    const genflow::TriangleMesh noisy =
        genflow::bench::noisy_torus_of_size(static_cast<int>(state.range(0)), 0.3);
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::implicit_fairing(noisy, {.steps = 5}).mesh.V.data());
    }
    state.counters["V"] = static_cast<double>(noisy.V.rows());
}

// Argument k: GMRES to a relative residual of 10^-k (4: what volume_controlled_fairing() asks).
void BM_VolumeFairingStep(benchmark::State& state) {
    const genflow::SurfaceAreaEnergy area;
    genflow::VolumeControlledMetric metric(
        {.lambda = 0.05, .tolerance = std::pow(10.0, -static_cast<double>(state.range(0)))});
    int iterations = 0;
    for (auto _ : state) {
        metric.update(horse());
        const auto linearization = area.linearize(horse());
        benchmark::DoNotOptimize(
            metric.shifted_gradient(linearization->A, dt(), area.differential(horse())));
        iterations = metric.last_iterations();
    }
    state.counters["gmres_iterations"] = iterations;
}

const Eigen::SparseMatrix<double>& fairing_matrix() {
    static const Eigen::SparseMatrix<double> A = [] {
        Eigen::SparseMatrix<double> S =
            genflow::mass_matrix(horse(), genflow::MassType::Barycentric) +
            dt() * genflow::cotan_stiffness(horse());
        S.makeCompressed();
        return S;
    }();
    return A;
}

template <typename Solver>
void solver_phases(benchmark::State& state) {
    const auto& A = fairing_matrix();
    const Eigen::MatrixXd B = horse().V;
    // 0 analyze, 1 factorize, 2 solve column by column, 3 solve the columns at once
    const int phase = static_cast<int>(state.range(0));
    Solver solver;
    solver.analyzePattern(A);
    solver.factorize(A);
    for (auto _ : state) {
        if (phase == 0) {
            solver.analyzePattern(A);
        } else if (phase == 1) {
            solver.factorize(A);
        } else if (phase == 2) {
            for (int c = 0; c < 3; ++c) {
                Eigen::VectorXd x = solver.solve(Eigen::VectorXd(B.col(c)));
                benchmark::DoNotOptimize(x.data());
            }
        } else {  // the three columns in one solve, as SpdSolver::solve()
            Eigen::MatrixXd X = solver.solve(B);
            benchmark::DoNotOptimize(X.data());
        }
    }
}

void BM_EigenLDLT(benchmark::State& state) {
    solver_phases<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(state);
}
#ifdef GENFLOW_BENCH_HAS_CHOLMOD
void BM_Cholmod(benchmark::State& state) {
    solver_phases<Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>>>(state);
}
#endif

}  // namespace

// The quasi-articulated metric's update() (its block Gram–Schmidt) and one gradient, on a
// sphere cut along x into a chain of 17 parts (17 hand parts' worth of fields): 642 vertices
// (argument 3, about a match's coarsest level, whose flows pay it at every step) and 41K (6).
void BM_ArticulatedMetricUpdate(benchmark::State& state) {
    const genflow::TriangleMesh mesh = genflow::make_icosphere(static_cast<int>(state.range(0)));
    constexpr int kParts = 17;
    Eigen::VectorXi labels(mesh.V.rows());
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        labels[i] = std::min(kParts - 1, static_cast<int>((mesh.V(i, 0) + 1) / 2 * kParts));
    }
    genflow::PartModel model;
    for (int k = 0; k < kParts; ++k) {
        model.parts.push_back(
            {"part" + std::to_string(k), k - 1, Eigen::Vector3d(-1 + 2.0 * k / kParts, 0, 0)});
    }
    model.weights = genflow::weights_from_labels(labels, kParts);
    genflow::SubspaceMetric metric = genflow::quasi_articulated_metric(mesh, model);
    for (auto _ : state) {
        metric.update(mesh);
        benchmark::DoNotOptimize(metric.gradient(mesh.V));
    }
}

// One H1 metric update and gradient at the size of a match's coarsest level (a 642-vertex
// icosphere; the TOSCA cat's is 471), which its flows pay at every step, thousands of steps.
void BM_H1StepCoarse(benchmark::State& state) {
    const genflow::TriangleMesh mesh = genflow::make_icosphere(3);
    const double h = genflow::mean_edge_length(mesh);
    genflow::H1Metric metric({.lambda = h * h});
    metric.update(mesh);
    for (auto _ : state) {
        metric.update(mesh);
        benchmark::DoNotOptimize(metric.gradient(mesh.V));
    }
}

BENCHMARK(BM_FairingStepFirst)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FairingStepLater)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FairingStepLaterInHalves)
    ->ArgName("alongside")
    ->DenseRange(0, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FairingAssembleOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FairingFiveStepsCurve)
    ->Apply(genflow::bench::cost_curve_sizes)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VolumeFairingStep)->Arg(10)->Arg(6)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_H1StepCoarse)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ArticulatedMetricUpdate)->Arg(3)->Arg(6)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EigenLDLT)->ArgName("phase")->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
#ifdef GENFLOW_BENCH_HAS_CHOLMOD
BENCHMARK(BM_Cholmod)->ArgName("phase")->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
#endif

BENCHMARK_MAIN();
