// SPDX-License-Identifier: MIT
// Time of a whole match() with the default options (h1 prior, global rigid alignment, start
// selection, guided coarsest flow, multiresolution): on the demo's generated pair (a limb bent
// at two joints and moved rigidly, 2562 vertices each side), and, with $GENFLOW_DATA, on the
// 28K-vertex TOSCA cat and the 13K-vertex MakeHuman body against their remeshed targets; and
// with the quasi-articulated prior on FAUST 000→001 (SMPL's 24 parts, 76 fields). Each
// reports the mean correspondence error over the target's bounding-box diagonal, so that a
// faster setting that matches worse shows in the same table. Also the time of the evaluation
// (correspondence_error()) of a match gone wrong, and of the embedding of a level in the next
// coarser one, along the surface and in the closest face of all; and of ZoomOut's nearest-row
// search in two spheres' spectral embeddings. The "TemplateCached" variants
// match with the template's analyses kept from an earlier match of it (TemplateCache, as
// `genflow batch` runs every target after the first): their time less the plain one's is what a
// batch saves per target.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <numeric>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "genflow/io/read_mesh.h"
#include "genflow/io/read_part_model.h"
#include "genflow/matching/correspondence_error.h"
#include "genflow/matching/match.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/laplacian_eigenbasis.h"
#include "genflow/operators/mesh_size.h"
#include "matching/functional_map.h"
#include "matching/intrinsic_start.h"

namespace {

struct MatchCase {
    genflow::TriangleMesh template_mesh;
    genflow::TriangleMesh target;
    Eigen::MatrixX3d truth;  // where each template vertex should land
    genflow::MatchOptions options{};
};

// The demo's pair: the target sampled elsewhere, bent at both joints and moved rigidly.
MatchCase generated_limb() {
    constexpr double kDegree = std::numbers::pi / 180;
    const std::vector<genflow::Joint> pose{
        {{1.0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 40 * kDegree, 0.4},
        {{-1.2, 0, 0}, {-1, 0, 0}, {0, 1, 0}, -30 * kDegree, 0.4}};
    genflow::Similarity motion;
    motion.rotation =
        Eigen::AngleAxisd(50 * kDegree, Eigen::Vector3d(1, 1, 1).normalized()).toRotationMatrix();
    motion.translation = Eigen::Vector3d(0.5, -1, 2);
    MatchCase pair{genflow::make_limb(4), genflow::make_limb(4, 7), {}};
    pair.target.V = motion.apply(genflow::bend_at_joints(pair.target.V, pose));
    pair.truth = motion.apply(genflow::bend_at_joints(pair.template_mesh.V, pose));
    return pair;
}

// $GENFLOW_DATA, else ../shared/data.
std::filesystem::path data_root() {
    const char* data = std::getenv("GENFLOW_DATA");
    return data != nullptr ? data : "../shared/data";
}

// A pair of $GENFLOW_DATA/pairs.json, by its file names; nothing without the data.
std::optional<MatchCase> data_pair(const std::string& template_file,
                                   const std::string& ground_truth_file,
                                   const std::string& remeshed_file) {
    const std::filesystem::path root = data_root();
    if (!std::filesystem::exists(root / template_file)) {
        return std::nullopt;
    }
    return MatchCase{genflow::read_mesh(root / template_file),
                     genflow::read_mesh(root / remeshed_file),
                     genflow::read_mesh(root / ground_truth_file).V};
}

// `cached`: with the template's analyses kept by a match of it before the timed ones.
void run(benchmark::State& state, const std::optional<MatchCase>& pair, bool cached = false) {
    if (!pair) {
        state.SkipWithError("needs $GENFLOW_DATA");
        return;
    }
    const double diagonal = genflow::bounding_box_diagonal(pair->target);
    genflow::MatchOptions options = pair->options;
    if (cached) {
        options.template_cache = std::make_shared<genflow::TemplateCache>();
        (void)genflow::match(pair->template_mesh, pair->target, options);
    }
    double error = 0;
    for (auto _ : state) {
        const genflow::MatchResult result =
            genflow::match(pair->template_mesh, pair->target, options);
        error = (result.deformed.V - pair->truth).rowwise().norm().mean() / diagonal;
    }
    state.counters["template_vertices"] = static_cast<double>(pair->template_mesh.V.rows());
    state.counters["target_vertices"] = static_cast<double>(pair->target.V.rows());
    state.counters["mean_error_percent"] = 100 * error;
}

void BM_MatchGeneratedLimb(benchmark::State& state) {
    static const std::optional<MatchCase> pair = generated_limb();
    run(state, pair);
}

void BM_MatchGeneratedLimbTemplateCached(benchmark::State& state) {
    static const std::optional<MatchCase> pair = generated_limb();
    run(state, pair, true);
}

const std::optional<MatchCase>& tosca_cat() {
    static const std::optional<MatchCase> pair =
        data_pair("matching/tosca/cat0.ply", "matching/tosca/cat4.ply",
                  "matching/remeshed/tosca_cat_0_4_target_remeshed.ply");
    return pair;
}

void BM_MatchTOSCACat(benchmark::State& state) {
    run(state, tosca_cat());
}

void BM_MatchTOSCACatTemplateCached(benchmark::State& state) {
    run(state, tosca_cat(), true);
}

// FAUST 000→001 with the quasi-articulated prior and SMPL's parts, as docs/eval matches it: its
// metric's update, at every flow step, dominated the match until the Gram–Schmidt ran on the
// Gram matrix of the fields.
void BM_MatchArticulatedFAUST(benchmark::State& state) {
    static const std::optional<MatchCase> pair = [] {
        std::optional<MatchCase> faust =
            data_pair("matching/faust/tr_reg_000.ply", "matching/faust/tr_reg_001.ply",
                      "matching/remeshed/faust_000_001_target_remeshed.ply");
        if (faust) {
            const std::filesystem::path parts = data_root() / "matching" / "faust";
            faust->options.prior = genflow::MatchPrior::Articulated;
            faust->options.parts = genflow::read_part_model(
                genflow::PartFiles{.tree = parts / "smpl_parts.json",
                                   .labels = parts / "smpl_part_labels.txt",
                                   .template_name = "tr_reg_000"},
                faust->template_mesh.V.rows());
        }
        return faust;
    }();
    run(state, pair);
}

void BM_MatchMakeHumanBody(benchmark::State& state) {
    static const std::optional<MatchCase> pair =
        data_pair("rigs/makehuman_body/body_rest.ply", "rigs/makehuman_body/body_pose1.ply",
                  "matching/remeshed/makehuman_body_rest_pose1_target_remeshed.ply");
    run(state, pair);
}

// The evaluation of a match gone wrong (correspondence_error(), its stranded test): every
// vertex of the generated limb (10242 vertices) put where another one is, at random.
void BM_CorrespondenceErrorOfAMatchGoneWrong(benchmark::State& state) {
    const genflow::TriangleMesh truth = genflow::make_limb(5);
    std::vector<Eigen::Index> other(static_cast<std::size_t>(truth.V.rows()));
    std::iota(other.begin(), other.end(), Eigen::Index{0});
    std::shuffle(other.begin(), other.end(), std::mt19937(1));
    const Eigen::MatrixX3d deformed = truth.V(other, Eigen::all);
    Eigen::Index stranded = 0;
    for (auto _ : state) {
        stranded = genflow::correspondence_error(deformed, truth).stranded_count;
    }
    state.counters["vertices"] = static_cast<double>(truth.V.rows());
    state.counters["stranded"] = static_cast<double>(stranded);
}

// The intrinsic start of a doubtful match's second opinion (detail::intrinsic_start()) on
// TOSCA michael standing and kneeling (52565 vertices each; each coarsened to about 1000
// vertices first, all-pairs geodesics, clique search, one functional map per candidate).
void BM_IntrinsicStartTOSCAMichaelKneeling(benchmark::State& state) {
    static const std::optional<MatchCase> pair =
        data_pair("matching/tosca/michael0.ply", "matching/tosca/michael2.ply",
                  "matching/tosca/michael2.ply");
    if (!pair) {
        state.SkipWithError("needs $GENFLOW_DATA");
        return;
    }
    std::optional<genflow::detail::IntrinsicStart> start;
    for (auto _ : state) {
        start = genflow::detail::intrinsic_start(pair->template_mesh, pair->target);
    }
    state.counters["landmarks"] = start ? start->landmarks : 0;
    state.counters["mean_distance_percent"] =
        start ? 100 * (start->placement - pair->truth).rowwise().norm().mean() /
                    genflow::bounding_box_diagonal(pair->target)
              : -1;
}

// A pyramid level's embedding in the next coarser one: the generated limb at 40962 vertices,
// coarsened 4×, as match() builds its pyramid (embed() along the surface), and the closest face
// of all for comparison.
const std::pair<genflow::TriangleMesh, genflow::CoarseMesh>& limb_level() {
    static const std::pair<genflow::TriangleMesh, genflow::CoarseMesh> level = [] {
        genflow::TriangleMesh fine = genflow::make_limb(6);
        genflow::CoarseMesh coarse = genflow::coarsen(fine, fine.V.rows() / 4);
        return std::pair{std::move(fine), std::move(coarse)};
    }();
    return level;
}

void BM_EmbedLevelAlongTheSurface(benchmark::State& state) {
    const auto& [fine, coarse] = limb_level();
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::embed(fine, coarse));
    }
    state.counters["vertices"] = static_cast<double>(fine.V.rows());
}

void BM_EmbedLevelInTheClosestFace(benchmark::State& state) {
    const auto& [fine, coarse] = limb_level();
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::embed(fine, coarse.mesh));
    }
    state.counters["vertices"] = static_cast<double>(fine.V.rows());
}

// ZoomOut's nearest-row search (detail::nearest_rows()) in the embeddings of two noisy 10K
// spheres, the first's functions through an orthogonal map, both weighted as ZoomOut weighs
// them, at `size` functions; the whole product −2·from·toᵀ it replaces is
// BM_WholeProductZoomOutEmbedding. The eigenbases are made once; the embeddings of a size
// before each benchmark's timed loop.
struct ZoomOutEmbeddings {
    Eigen::MatrixXd from, to;
};

ZoomOutEmbeddings zoom_out_embeddings(Eigen::Index size) {
    static const auto bases = [] {
        const genflow::TriangleMesh sphere = genflow::make_icosphere(5);
        const double noise = 0.1 * genflow::mean_edge_length(sphere);
        return std::pair{genflow::laplacian_eigenbasis(genflow::add_noise(sphere, noise, 1), 61),
                         genflow::laplacian_eigenbasis(genflow::add_noise(sphere, noise, 2), 61)};
    }();
    const Eigen::RowVectorXd weights =
        genflow::detail::embedding_weights(bases.second.values.segment(1, size));
    std::mt19937 random(3);
    std::normal_distribution<double> normal;
    const Eigen::MatrixXd turn =
        Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::NullaryExpr(size, size, [&] {
            return normal(random);
        })).householderQ();
    return {bases.first.functions.middleCols(1, size) * turn * weights.asDiagonal(),
            bases.second.functions.middleCols(1, size) * weights.asDiagonal()};
}

void BM_NearestRowsZoomOutEmbedding(benchmark::State& state) {
    const ZoomOutEmbeddings e = zoom_out_embeddings(state.range(0));
    for (auto _ : state) {
        benchmark::DoNotOptimize(genflow::detail::nearest_rows(e.from, e.to).data());
    }
    state.counters["rows"] = static_cast<double>(e.from.rows());
}

// The whole product and its row minima, as the search did before it skipped blocks.
void BM_WholeProductZoomOutEmbedding(benchmark::State& state) {
    const ZoomOutEmbeddings e = zoom_out_embeddings(state.range(0));
    for (auto _ : state) {
        const Eigen::MatrixXd distances =
            (-2 * e.from * e.to.transpose()).rowwise() + e.to.rowwise().squaredNorm().transpose();
        Eigen::VectorXd smallest = distances.rowwise().minCoeff();
        benchmark::DoNotOptimize(smallest.data());
    }
}

}  // namespace

BENCHMARK(BM_NearestRowsZoomOutEmbedding)->Arg(10)->Arg(30)->Arg(60)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WholeProductZoomOutEmbedding)
    ->Arg(10)
    ->Arg(30)
    ->Arg(60)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EmbedLevelAlongTheSurface)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EmbedLevelInTheClosestFace)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IntrinsicStartTOSCAMichaelKneeling)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_CorrespondenceErrorOfAMatchGoneWrong)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_MatchGeneratedLimb)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_MatchGeneratedLimbTemplateCached)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_MatchTOSCACat)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_MatchTOSCACatTemplateCached)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_MatchMakeHumanBody)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_MatchArticulatedFAUST)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
