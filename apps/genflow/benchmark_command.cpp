// SPDX-License-Identifier: MIT
// genflow benchmark DIR: the standard protocol of the public correspondence benchmarks
// (FAUST_r, SCAPE_r, ...) on a directory of shapes with .vts reference points: match a seeded
// sample of ordered pairs (or all), measure each reference point's geodesic error on the target
// over √area (genflow/evaluation/geodesic_error.h), flag pairs matched mirror-wise, and report
// the mean × 100 within and across subjects, the PCK curve and the time per pair.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "cli_support.h"
#include "commands.h"
#include "genflow/evaluation/benchmark_pairs.h"
#include "genflow/evaluation/geodesic_error.h"
#include "genflow/evaluation/reference_landmarks.h"
#include "genflow/evaluation/reference_symmetry.h"
#include "genflow/evaluation/scan_defects.h"
#include "genflow/evaluation/single_view.h"
#include "genflow/exceptions.h"
#include "genflow/io/atomic_file.h"
#include "genflow/io/mesh_format.h"
#include "genflow/io/read_reference_points.h"
#include "genflow/io/write_correspondences.h"
#include "genflow/matching/correspondence.h"
#include "genflow/matching/spectral_map.h"
#include "genflow/mesh/face_selection.h"
#include "genflow/operators/area.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/normals.h"
#include "genflow/operators/volume.h"
#include "genflow/spatial/point_cloud_surface.h"
#include "match_flags.h"
#include "number_checks.h"
#include "shard.h"

namespace genflow::cli {

namespace {

// How each pair's target is given to the matcher.
struct TargetForm {
    bool points = false;      // its vertices alone, as a point cloud
    bool normals = false;     // the points with the mesh's vertex normals, as a scanner gives them
    double noise = 0;         // Gaussian noise on the points or vertices, σ in mean edge lengths
    bool view = false;        // only the faces facing a camera (single_view()), from a random side
    int holes = 0;            // holes punched (ScanDefects::holes)
    int fragments = 0;        // loose fragments added (ScanDefects::fragments)
    bool ragged = false;      // a ragged boundary (ScanDefects::ragged_boundary)
    double out_of_frame = 0;  // the share cut off by the frame (ScanDefects::out_of_frame)

    // Whether the target is given as the mesh is, so that the map's points lie on its faces.
    [[nodiscard]] bool as_is() const {
        return !points && !view && noise == 0 && holes == 0 && fragments == 0 && !ragged &&
               out_of_frame == 0;
    }
    // Whether some of the mesh's surface is left out, so that the rows measure the seen part.
    [[nodiscard]] bool shows_part() const {
        return view || holes > 0 || ragged || out_of_frame > 0;
    }
};

struct BenchmarkOptions {
    std::string directory;
    std::size_t pairs = 100;
    bool all = false;
    std::uint64_t seed = 1;
    int subject_size = 0;  // 0: one subject
    std::string output_dir;
    bool resume = false;
    std::string shard;  // "i/N"; empty: every pair
    bool json = false;
    std::string method = "match";
    int landmarks = 0;  // per pair, from the ground truth (reference_landmarks())
    TargetForm target;
    MatchFlags flags;
};

// The PCK curve's thresholds, in units of √area: 0 to 0.25 by 0.005 (the range of the
// published plots), the histogram of each pair kept at that resolution.
constexpr double kPckStep = 0.005;
constexpr int kPckBins = 50;

struct Shape {
    std::string name;  // the file's stem
    TriangleMesh mesh;
    std::vector<Eigen::Index> reference;  // the vertex of each reference point
};

// Every mesh file of `directory` with a .vts file of the same stem beside it, by name.
std::vector<Shape> read_shapes(const std::filesystem::path& directory) {
    std::error_code error;
    if (!std::filesystem::is_directory(directory, error)) {
        throw IoError(directory.string() + ": not a directory");
    }
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
        const std::filesystem::path& path = entry.path();
        if (mesh_format_from_extension(path) &&
            std::filesystem::exists(std::filesystem::path(path).replace_extension(".vts"))) {
            files.push_back(path);
        }
    }
    std::sort(files.begin(), files.end());
    std::vector<Shape> shapes;
    for (const std::filesystem::path& path : files) {
        LoadedMesh loaded = load_mesh(path);
        std::vector<Eigen::Index> reference = read_reference_points(
            std::filesystem::path(path).replace_extension(".vts"), loaded.mesh.V.rows());
        if (!shapes.empty() && reference.size() != shapes.front().reference.size()) {
            throw IoError(std::filesystem::path(path).replace_extension(".vts").string() + ": " +
                          std::to_string(reference.size()) + " reference points, " +
                          shapes.front().name + " has " +
                          std::to_string(shapes.front().reference.size()));
        }
        shapes.push_back({path.stem().string(), std::move(loaded.mesh), std::move(reference)});
    }
    if (shapes.size() < 2) {
        throw IoError(directory.string() +
                      ": fewer than two meshes with a .vts file of reference points beside them");
    }
    return shapes;
}

ReferenceSymmetry symmetry_of(const std::vector<Shape>& shapes) {
    std::vector<Eigen::MatrixX3d> positions;
    std::vector<double> units;
    for (const Shape& shape : shapes) {
        positions.emplace_back(shape.mesh.V(shape.reference, Eigen::all));
        units.push_back(std::sqrt(surface_area(shape.mesh)));
    }
    return estimate_reference_symmetry(positions, units);
}

double mean_of(const Eigen::VectorXd& values) {
    return values.mean();
}

// The mean of the reference points' errors where the target as given holds their vertex, or
// null where it holds none.
nlohmann::json mean_where_seen(const Eigen::VectorXd& errors,
                               const std::vector<Eigen::Index>& reference,
                               const std::vector<bool>& seen) {
    double sum = 0;
    int count = 0;
    for (std::size_t k = 0; k < reference.size(); ++k) {
        if (seen[static_cast<std::size_t>(reference[k])]) {
            sum += errors[static_cast<Eigen::Index>(k)];
            ++count;
        }
    }
    return count > 0 ? nlohmann::json(sum / count) : nlohmann::json(nullptr);
}

std::vector<int> histogram_of(const Eigen::VectorXd& errors) {
    std::vector<int> bins(kPckBins + 1, 0);  // the last: above the curve's range
    for (const double e : errors) {
        ++bins[static_cast<std::size_t>(std::min<double>(kPckBins, std::floor(e / kPckStep)))];
    }
    return bins;
}

// Each of `vertices` as a point of `mesh`: a face of its and barycentric coordinates there.
std::vector<SurfacePoint> vertex_points(const TriangleMesh& mesh,
                                        const std::vector<Eigen::Index>& vertices) {
    std::vector<std::pair<Eigen::Index, int>> corner(static_cast<std::size_t>(mesh.V.rows()),
                                                     {-1, 0});
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            corner[static_cast<std::size_t>(mesh.F(f, c))] = {f, c};
        }
    }
    std::vector<SurfacePoint> points(vertices.size());
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        const auto [face, c] = corner[static_cast<std::size_t>(vertices[i])];
        points[i].face = face;
        points[i].barycentric = Eigen::Vector3d::Unit(c);
        points[i].point = mesh.V.row(vertices[i]).transpose();
    }
    return points;
}

struct PairMap {
    std::vector<SurfacePoint> points;  // per template vertex
    double seconds = 0;
    nlohmann::json details = nlohmann::json::object();  // what the method reports of itself
    // A match's closest points, where the counterparts' stage chose other points.
    std::vector<SurfacePoint> closest = {};
    // The closest points of the reading the match did not keep, where it read twice.
    std::vector<SurfacePoint> other_reading = {};
    double processor_seconds = 0;  // of the whole process: with one thread a pair, the pair's
    // Per target vertex, whether the target as given holds it (a single view); empty: all.
    std::vector<bool> seen = {};
    std::optional<std::size_t> landmarks_given = {};  // of the pair, where landmarks were asked
};

// The share of `mesh`'s area that `seen` (made of it) still holds: its faces on the mesh's own
// vertices where they were, not its fragments' nor its noise.
double seen_area_share(const TriangleMesh& seen, const TriangleMesh& mesh) {
    const TriangleMesh kept{mesh.V, faces_where(seen.F, [&](Eigen::Index f) {
                                return seen.F.row(f).maxCoeff() < mesh.V.rows();
                            })};
    return surface_area(kept) / surface_area(mesh);
}

// A seed of the pair's names (FNV-1a), so that a pair's target is made the same in every run.
std::uint64_t pair_seed(const Shape& from, const Shape& to) {
    std::uint64_t seed = 14695981039346656037ULL;
    for (const char c : from.name + ">" + to.name) {
        seed = (seed ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
    }
    return seed;
}

// `to`'s vertices as a point cloud, each moved by Gaussian noise of σ = `noise` mean edge
// lengths.
Eigen::MatrixX3d cloud_of(const Shape& to, double noise, std::uint64_t seed) {
    Eigen::MatrixX3d cloud = to.mesh.V;
    if (noise > 0) {
        std::mt19937_64 random(seed);
        std::normal_distribution<double> normal(0, noise * mean_edge_length(to.mesh));
        for (Eigen::Index i = 0; i < cloud.rows(); ++i) {
            for (int c = 0; c < 3; ++c) {
                cloud(i, c) += normal(random);
            }
        }
    }
    return cloud;
}

// A pair's target in its form: the part of the target mesh shown (on the mesh's own vertices,
// with any fragments after them), and what the matcher is given, the same mesh or, as a point
// cloud, the surface made on the shown part's points.
struct FormedTarget {
    TriangleMesh shown;
    TriangleMesh matched;
};

// `mesh`'s vertices on faces, as a point cloud moved by Gaussian noise of σ = `noise` mean
// edge lengths of `to`, with the vertex normals of `to` where `normals`.
TriangleMesh cloud_surface_of(const TriangleMesh& mesh, const Shape& to, bool normals, double noise,
                              std::uint64_t seed) {
    const std::vector<Eigen::Index> rows = vertices_used_by(mesh.F, mesh.V.rows());
    const Eigen::MatrixX3d cloud = cloud_of(to, noise, seed)(rows, Eigen::all);
    if (!normals) {
        return point_cloud_surface(cloud, Eigen::MatrixX3d(0, 3));
    }
    return point_cloud_surface(cloud, vertex_normals(to.mesh)(rows, Eigen::all));
}

// The target as `form` gives it to the matcher.
FormedTarget target_in_form(const Shape& from, const Shape& to, const TargetForm& form) {
    const std::uint64_t seed = pair_seed(from, to);
    const TriangleMesh seen = form.view ? single_view(to.mesh, view_direction(seed)) : to.mesh;
    if (form.points) {
        return {seen, cloud_surface_of(seen, to, form.normals, form.noise, seed)};
    }
    const ScanDefects defects{.out_of_frame = form.out_of_frame,
                              .holes = form.holes,
                              .fragments = form.fragments,
                              .ragged_boundary = form.ragged,
                              .noise = form.noise};
    // The defects' draw apart from the view's, so that a view is the same with or without them.
    TriangleMesh shown = with_scan_defects(seen, defects, seed + 1);
    return {shown, shown};
}

// The map of `method` alone, timed by the wall clock: the deformed template's counterparts
// ("match"), or the intrinsic vertex map alone ("spectral-map", spectral_map()).
PairMap map_of_method(const std::string& method, const Shape& from, const Shape& to,
                      const MatchOptions& options, const TargetForm& target,
                      const FormedTarget& formed) {
    const TriangleMesh& matched = formed.matched;
    if (method == "spectral-map") {
        const auto start = std::chrono::steady_clock::now();
        const SpectralMap map = spectral_map(from.mesh, to.mesh);
        return {vertex_points(to.mesh, map.target_vertex),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                {{"orientation_ratio", map.orientation_ratio}, {"basis_size", map.basis_size}}};
    }
    // A target in another form is matched as it is given; the map's points are then measured
    // on the target mesh, where they lie nearest.
    const MatchResult result = match(from.mesh, matched, options);
    std::vector<SurfacePoint> points = match_correspondence(result, matched);
    if (!target.as_is()) {
        points = closest_points(positions_of(points), to.mesh);
    }
    PairMap map{std::move(points), result.seconds, match_choices(result)};
    if (target.shows_part()) {
        map.seen = vertices_on_faces(formed.shown.F, formed.shown.V.rows());
        map.details["seen_area_share"] = seen_area_share(formed.shown, to.mesh);
        // A template that folds its unseen side onto the view loses its volume.
        const double volume = enclosed_volume(from.mesh);
        map.details["volume_kept"] = volume > 0
                                         ? nlohmann::json(enclosed_volume(result.deformed) / volume)
                                         : nlohmann::json();
    }
    map.details["stage_times"] = stage_times_json(result);
    if (result.counterparts_moved) {
        map.closest = closest_points(result.deformed.V, to.mesh);
    }
    if (result.other_reading) {
        map.other_reading = closest_points(*result.other_reading, to.mesh);
    }
    return map;
}

// The target forms that can be made together, and only for the matcher.
void check_target_form(const TargetForm& target, const std::string& method) {
    if (target.normals && !target.points) {
        throw InvalidInput(
            "--target-normals: normals are given to a point cloud (--target-points)");
    }
    if (target.points &&
        (target.holes > 0 || target.fragments > 0 || target.ragged || target.out_of_frame > 0)) {
        throw InvalidInput(
            "--target-holes, --target-fragments, --target-ragged, --target-out-of-frame: made on "
            "a mesh, not with --target-points");
    }
    if (target.ragged && !target.view && target.holes == 0 && target.out_of_frame == 0) {
        throw InvalidInput(
            "--target-ragged: needs a boundary to make ragged (--target-view, --target-holes or "
            "--target-out-of-frame)");
    }
    if (!target.as_is() && method != "match") {
        throw InvalidInput(
            "--target-points, --target-view, --target-noise, --target-holes, --target-fragments, "
            "--target-ragged, --target-out-of-frame: only --method match takes a target in another "
            "form");
    }
}

// The processor time this process has used, all threads together.
double processor_seconds() {
    return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// `count` landmarks of the pair from its ground truth (reference_landmarks()). Onto a target that
// shows part of the surface, among the reference points it holds: a user clicks what a scan
// shows.
std::vector<Landmark> landmarks_of(const Shape& from, const Shape& to, const TargetForm& form,
                                   const TriangleMesh& shown, int count) {
    if (!form.shows_part()) {
        return reference_landmarks(from.mesh, from.reference, to.mesh, to.reference, count);
    }
    const std::vector<bool> seen = vertices_on_faces(shown.F, shown.V.rows());
    std::vector<Eigen::Index> from_seen;
    std::vector<Eigen::Index> to_seen;
    for (std::size_t k = 0; k < to.reference.size(); ++k) {
        if (seen[static_cast<std::size_t>(to.reference[k])]) {
            from_seen.push_back(from.reference[k]);
            to_seen.push_back(to.reference[k]);
        }
    }
    if (from_seen.empty()) {
        return {};
    }
    return reference_landmarks(from.mesh, from_seen, to.mesh, to_seen,
                               std::min(count, static_cast<int>(from_seen.size())));
}

// The map of `method` onto the target in `form`, with `landmarks` of the pair given
// (landmarks_of()), timed by the processor clock too: a benchmark shares its machine, and
// processor time does not grow while the pair waits for a core.
PairMap map_of(const std::string& method, const Shape& from, const Shape& to,
               const MatchOptions& options, const TargetForm& form, int landmarks) {
    const double processor_start = processor_seconds();
    const FormedTarget target = target_in_form(from, to, form);
    MatchOptions pair_options = options;
    if (landmarks > 0) {
        pair_options.landmarks.points = landmarks_of(from, to, form, target.shown, landmarks);
    }
    PairMap map = map_of_method(method, from, to, pair_options, form, target);
    map.processor_seconds = processor_seconds() - processor_start;
    if (landmarks > 0) {
        map.landmarks_given = pair_options.landmarks.points.size();
    }
    return map;
}

// Maps one pair and measures it; writes the map of every template vertex to `map_file`
// (write_correspondences()) unless it is empty.
nlohmann::json run_pair(const Shape& from, const Shape& to, bool within,
                        const ReferenceSymmetry& symmetry, const std::string& method,
                        const TargetForm& target, const MatchOptions& options, int landmarks,
                        const std::filesystem::path& map_file) {
    const PairMap result = map_of(method, from, to, options, target, landmarks);
    const std::vector<SurfacePoint>& map = result.points;
    if (!map_file.empty()) {
        write_correspondences(map_file, map);
    }
    const GeodesicErrorMeasure measure(to.mesh);
    const GeodesicErrors errors = measure.errors_at(map, from.reference, to.reference);
    nlohmann::json row = {{"from", from.name},
                          {"to", to.name},
                          {"within_subject", within},
                          {"mean", mean_of(errors.to_vertex)},
                          {"mean_point_map", mean_of(errors.to_point)},
                          {"histogram", histogram_of(errors.to_vertex)},
                          {"seconds", result.seconds},
                          {"processor_seconds", result.processor_seconds},
                          {"details", result.details}};
    if (!result.seen.empty()) {
        row["mean_seen"] = mean_where_seen(errors.to_vertex, to.reference, result.seen);
    }
    if (result.landmarks_given) {
        row["landmarks_given"] = *result.landmarks_given;
    }
    if (!result.closest.empty()) {
        row["mean_closest_points"] =
            mean_of(measure.errors_at(result.closest, from.reference, to.reference).to_vertex);
    }
    if (!result.other_reading.empty()) {
        row["mean_other_reading"] = mean_of(
            measure.errors_at(result.other_reading, from.reference, to.reference).to_vertex);
    }
    if (symmetry.found()) {
        std::vector<Eigen::Index> mirrored(to.reference.size());
        for (std::size_t k = 0; k < mirrored.size(); ++k) {
            mirrored[k] = to.reference[static_cast<std::size_t>(symmetry.mirror[k])];
        }
        const double mirror_mean =
            mean_of(measure.errors_at(map, from.reference, mirrored).to_vertex);
        row["mean_against_mirror"] = mirror_mean;
        row["mirrored"] = mirror_mean < row["mean"].get<double>();
    }
    return row;
}

// The file of a pair's result in --output-dir, and (`extension` ".map.txt") of its map.
std::filesystem::path pair_file(const std::filesystem::path& output_dir, const Shape& from,
                                const Shape& to, const char* extension = ".json") {
    return output_dir / "pairs" / (from.name + "-" + to.name + extension);
}

// A pair's result from an earlier run (--resume), if its file is complete.
std::optional<nlohmann::json> earlier_result(const std::filesystem::path& file) {
    std::ifstream stream(file);
    if (!stream) {
        return std::nullopt;
    }
    const nlohmann::json row = nlohmann::json::parse(stream, nullptr, false);
    if (row.is_discarded() || !row.contains("mean") || !row.contains("histogram")) {
        return std::nullopt;
    }
    return row;
}

// Per stage of the matcher (MatchResult::stage_times), its mean wall and processor time over
// `rows`, a row without the stage counting 0, in the order the stages first ran.
nlohmann::json stage_times_mean(const std::vector<nlohmann::json>& rows) {
    std::vector<std::string> stages;
    std::vector<std::pair<double, double>> sums;  // wall, processor
    for (const nlohmann::json& row : rows) {
        const nlohmann::json& details = row.value("details", nlohmann::json::object());
        for (const nlohmann::json& time : details.value("stage_times", nlohmann::json::array())) {
            const auto stage = time["stage"].get<std::string>();
            const auto at = std::find(stages.begin(), stages.end(), stage) - stages.begin();
            if (at == static_cast<std::ptrdiff_t>(stages.size())) {
                stages.push_back(stage);
                sums.emplace_back(0, 0);
            }
            sums[static_cast<std::size_t>(at)].first += time["seconds"].get<double>();
            sums[static_cast<std::size_t>(at)].second += time["processor_seconds"].get<double>();
        }
    }
    nlohmann::json means = nlohmann::json::array();
    const auto n = static_cast<double>(std::max<std::size_t>(rows.size(), 1));
    for (std::size_t k = 0; k < stages.size(); ++k) {
        means.push_back({{"stage", stages[k]},
                         {"seconds_mean", sums[k].first / n},
                         {"processor_seconds_mean", sums[k].second / n}});
    }
    return means;
}

// Of the rows that measure the seen part (--target-view): its mean and worst pair, or null.
nlohmann::json seen_summary(const std::vector<nlohmann::json>& rows) {
    double sum = 0;
    double worst = 0;
    int count = 0;
    for (const nlohmann::json& row : rows) {
        if (row.contains("mean_seen") && row["mean_seen"].is_number()) {
            sum += row["mean_seen"].get<double>();
            worst = std::max(worst, row["mean_seen"].get<double>());
            ++count;
        }
    }
    if (count == 0) {
        return nullptr;
    }
    return {{"pairs", count}, {"mean", sum / count}, {"worst_pair", worst}};
}

// The figures of a set of pairs' rows.
nlohmann::json summary_of(const std::vector<nlohmann::json>& rows) {
    double sum = 0;
    double sum_point = 0;
    double seconds = 0;
    double processor = 0;
    double slowest = 0;
    int mirrored = 0;
    std::vector<double> means;
    std::vector<long> bins(kPckBins + 1, 0);
    for (const nlohmann::json& row : rows) {
        means.push_back(row["mean"].get<double>());
        sum += means.back();
        sum_point += row["mean_point_map"].get<double>();
        seconds += row["seconds"].get<double>();
        slowest = std::max(slowest, row["seconds"].get<double>());
        processor += row.value("processor_seconds", 0.0);  // absent in rows of older builds
        mirrored += row.value("mirrored", false) ? 1 : 0;
        for (std::size_t b = 0; b < bins.size(); ++b) {
            bins[b] += row["histogram"][b].get<long>();
        }
    }
    const auto n = static_cast<double>(rows.size());
    std::sort(means.begin(), means.end());
    std::vector<double> pck;
    long below = 0;
    long total = 0;
    for (const long count : bins) {
        total += count;
    }
    for (int b = 0; b < kPckBins; ++b) {
        below += bins[static_cast<std::size_t>(b)];
        pck.push_back(total > 0 ? static_cast<double>(below) / static_cast<double>(total) : 0);
    }
    return {{"pairs", rows.size()},
            {"mean", rows.empty() ? 0 : sum / n},
            {"mean_point_map", rows.empty() ? 0 : sum_point / n},
            {"median_pair", rows.empty() ? 0 : means[means.size() / 2]},
            {"worst_pair", rows.empty() ? 0 : means.back()},
            {"mirrored", mirrored},
            {"pck", pck},
            {"seconds_mean", rows.empty() ? 0 : seconds / n},
            {"seconds_max", slowest},
            {"processor_seconds_mean", rows.empty() ? 0 : processor / n},
            {"stage_times_mean", stage_times_mean(rows)},
            {"seen", seen_summary(rows)}};
}

void print_summary_row(const char* set, const nlohmann::json& s) {
    if (s["pairs"].get<std::size_t>() == 0) {
        return;
    }
    const auto& pck = s["pck"];
    // PCK at 0.025, 0.05 and 0.1 of √area: the curve's value at the end of bins 4, 9 and 19.
    std::printf(
        "| %s | %zu | %.2f | %.2f | %.2f | %.2f | %d | %.1f / %.1f / %.1f %% | %.1f s (%.1f s) "
        "|\n",
        set, s["pairs"].get<std::size_t>(), 100 * s["mean"].get<double>(),
        100 * s["mean_point_map"].get<double>(), 100 * s["median_pair"].get<double>(),
        100 * s["worst_pair"].get<double>(), s["mirrored"].get<int>(), 100 * pck[4].get<double>(),
        100 * pck[9].get<double>(), 100 * pck[19].get<double>(), s["seconds_mean"].get<double>(),
        s["seconds_max"].get<double>());
}

// The sample of ordered pairs the options ask for (and this shard's share of it).
std::vector<ShapePair> sample_of(const BenchmarkOptions& options, std::size_t shapes) {
    std::vector<int> subjects(shapes, 0);
    for (std::size_t s = 0; s < shapes && options.subject_size > 0; ++s) {
        subjects[s] = static_cast<int>(s) / options.subject_size;
    }
    return shard_of(
        benchmark_pairs(subjects, options.all ? std::nullopt : std::optional(options.pairs),
                        options.seed),
        options.shard);
}

// One pair's row: read back from --output-dir with --resume, else mapped, measured and kept
// there. A solver failure is a row too ("failed"), and the benchmark goes on.
nlohmann::json row_of(const BenchmarkOptions& options, const Shape& from, const Shape& to,
                      bool within, const ReferenceSymmetry& symmetry,
                      const MatchOptions& match_options) {
    const std::filesystem::path output_dir(options.output_dir);
    if (options.resume) {
        if (std::optional<nlohmann::json> row = earlier_result(pair_file(output_dir, from, to))) {
            return *row;
        }
    }
    nlohmann::json row;
    try {
        row = run_pair(from, to, within, symmetry, options.method, options.target, match_options,
                       options.landmarks,
                       output_dir.empty() ? std::filesystem::path()
                                          : pair_file(output_dir, from, to, ".map.txt"));
    } catch (const SolverError& e) {
        row = {
            {"from", from.name}, {"to", to.name}, {"within_subject", within}, {"failed", e.what()}};
    }
    if (!output_dir.empty() && !row.contains("failed")) {
        write_file_atomically(pair_file(output_dir, from, to), row.dump() + "\n");
    }
    return row;
}

void print_row(const nlohmann::json& row) {
    // Names from file names, and messages that quote them, escaped (printable()).
    const std::string pair =
        printable(row["from"].get<std::string>() + " → " + row["to"].get<std::string>());
    const char* kind = row["within_subject"].get<bool>() ? "within" : "across";
    if (row.contains("failed")) {
        std::printf("| %s | %s | failed: %s | | | |\n", pair.c_str(), kind,
                    printable(row["failed"].get<std::string>()).c_str());
    } else {
        std::printf("| %s | %s | %.2f | %.2f | %s | %.1f s |\n", pair.c_str(), kind,
                    100 * row["mean"].get<double>(), 100 * row["mean_point_map"].get<double>(),
                    row.contains("mirrored") ? (row["mirrored"].get<bool>() ? "yes" : "no") : "?",
                    row["seconds"].get<double>());
    }
    std::fflush(stdout);
}

nlohmann::json summary_json(const BenchmarkOptions& options, std::size_t shapes,
                            const ReferenceSymmetry& symmetry,
                            const std::vector<nlohmann::json>& rows) {
    std::vector<nlohmann::json> all;
    std::vector<nlohmann::json> within;
    std::vector<nlohmann::json> across;
    int failed = 0;
    for (const nlohmann::json& row : rows) {
        if (row.contains("failed")) {
            ++failed;
            continue;
        }
        all.push_back(row);
        (row["within_subject"].get<bool>() ? within : across).push_back(row);
    }
    return {{"directory", options.directory},
            {"shapes", shapes},
            {"seed", options.seed},
            {"subject_size", options.subject_size},
            {"shard", options.shard},
            {"method", options.method},
            {"landmarks", options.landmarks},
            {"target_points", options.target.points},
            {"target_normals", options.target.normals},
            {"target_noise", options.target.noise},
            {"target_view", options.target.view},
            {"target_holes", options.target.holes},
            {"target_fragments", options.target.fragments},
            {"target_ragged", options.target.ragged},
            {"target_out_of_frame", options.target.out_of_frame},
            {"geodesics", "shortest paths along the edges (Dijkstra)"},
            {"unit", "sqrt(area) of the target"},
            {"pck_step", kPckStep},
            {"symmetry_residual", symmetry.residual},
            {"symmetry_found", symmetry.found()},
            {"failed", failed},
            {"all", summary_of(all)},
            {"within_subjects", summary_of(within)},
            {"across_subjects", summary_of(across)},
            {"rows", rows}};
}

// Where a pair's processor time went, stage by stage (a method without stages prints nothing).
void print_stage_times(const nlohmann::json& all) {
    const double total = all["processor_seconds_mean"].get<double>();
    if (all["stage_times_mean"].empty() || !(total > 0)) {
        return;
    }
    std::printf("\n| stage | processor time, mean a pair | share |\n|---|---:|---:|\n");
    for (const nlohmann::json& stage : all["stage_times_mean"]) {
        const double seconds = stage["processor_seconds_mean"].get<double>();
        std::printf("| %s | %.2f s | %.1f %% |\n", stage["stage"].get<std::string>().c_str(),
                    seconds, 100 * seconds / total);
    }
}

void print_summary(const nlohmann::json& summary) {
    std::printf(
        "\n| pairs | count | error ×100 | point map ×100 | median pair | worst pair | mirrored | "
        "PCK at 2.5 / 5 / 10 %% of √area | time mean (max) |\n"
        "|---|---:|---:|---:|---:|---:|---:|---|---|\n");
    print_summary_row("all", summary["all"]);
    print_summary_row("within subjects", summary["within_subjects"]);
    print_summary_row("across subjects", summary["across_subjects"]);
    if (summary["failed"].get<int>() > 0) {
        std::printf("\n%d pair(s) failed (not in the figures).\n", summary["failed"].get<int>());
    }
    print_stage_times(summary["all"]);
    std::printf(
        "\nError: the mean over all reference points of the geodesic distance on the target "
        "(shortest paths along its edges) from where the map put each one to where it belongs, "
        "over √area of the target, × 100, the map's points snapped to their faces' nearest "
        "corners as a vertex-to-vertex map would be (the published tables' protocol); point "
        "map: the points as they are. Mirrored: pairs whose error is smaller against the "
        "mirrored reference points (symmetry residual %.4f √area%s).\n",
        summary["symmetry_residual"].get<double>(),
        summary["symmetry_found"].get<bool>() ? "" : ": no symmetry, not measured");
}

// The stages: the set, the sample, each pair's row, the summary. Exits 1 if a pair failed.
void run_benchmark(const BenchmarkOptions& options) {
    if (options.resume && options.output_dir.empty()) {
        throw InvalidInput("--resume needs --output-dir (where the earlier results are)");
    }
    const std::vector<Shape> shapes = read_shapes(options.directory);
    if (options.landmarks > 0 &&
        static_cast<std::size_t>(options.landmarks) > shapes.front().reference.size()) {
        throw InvalidInput("--landmarks: " + std::to_string(options.landmarks) +
                           " asked, the shapes have " +
                           std::to_string(shapes.front().reference.size()) + " reference points");
    }
    check_target_form(options.target, options.method);
    const std::vector<ShapePair> pairs = sample_of(options, shapes.size());
    const ReferenceSymmetry symmetry = symmetry_of(shapes);
    const MatchOptions match_options = resolved(options.flags, false);
    if (!options.output_dir.empty()) {
        create_output_directory(std::filesystem::path(options.output_dir) / "pairs");
    }
    if (!options.json) {
        std::printf(
            "| pair | subjects | error ×100 | point map ×100 | mirrored | time |\n"
            "|---|---|---:|---:|---|---:|\n");
    }
    std::vector<nlohmann::json> rows;
    for (const ShapePair& pair : pairs) {
        rows.push_back(row_of(options, shapes[static_cast<std::size_t>(pair.from)],
                              shapes[static_cast<std::size_t>(pair.to)], pair.within_subject,
                              symmetry, match_options));
        if (!options.json) {
            print_row(rows.back());
        }
    }
    const nlohmann::json summary = summary_json(options, shapes.size(), symmetry, rows);
    if (!options.output_dir.empty()) {
        write_file_atomically(std::filesystem::path(options.output_dir) / "summary.json",
                              summary.dump(2) + "\n");
    }
    if (options.json) {
        std::cout << summary.dump(2) << '\n';
    } else {
        print_summary(summary);
    }
    if (summary["failed"].get<int>() > 0) {
        throw SolverError("benchmark: " + std::to_string(summary["failed"].get<int>()) +
                          " pair(s) failed; the figures leave them out");
    }
}

}  // namespace

void register_benchmark_command(CLI::App& app) {
    auto options = std::make_shared<BenchmarkOptions>();
    auto* command = app.add_subcommand(
        "benchmark",
        "Run the matcher on a correspondence benchmark (a directory of meshes, each with a .vts "
        "file of 1-based reference vertices, as FAUST_r publishes them) with the standard "
        "protocol: the geodesic error of every reference point over √area of the target, × 100, "
        "within and across subjects, the PCK curve, mirrored pairs and the time per pair");
    command->add_option("directory", options->directory, "The benchmark's shapes")->required();
    command->add_option("--pairs", options->pairs, "Ordered pairs to draw (half within subjects)")
        ->check(number_in(1, 1000000))
        ->capture_default_str();
    command->add_flag("--all", options->all, "Every ordered pair instead of a sample");
    command->add_option("--seed", options->seed, "Seed of the sample")->capture_default_str();
    command
        ->add_option("--subject-size", options->subject_size,
                     "Shapes in name order form subjects of this many (FAUST: 10); 0: one subject")
        ->check(non_negative_number())
        ->capture_default_str();
    command->add_option("--output-dir", options->output_dir,
                        "Write each pair's result (pairs/FROM-TO.json), its map (pairs/"
                        "FROM-TO.map.txt, as match --correspondence writes it) and summary.json "
                        "there");
    command->add_flag("--resume", options->resume,
                      "Take the pairs already in --output-dir from there instead of matching "
                      "them again");
    command->add_option("--shard", options->shard,
                        "Only the pairs at positions i, i + N, ... of the sample (i/N), so that N "
                        "processes share it; a last run with --resume summarizes them all");
    command
        ->add_option("--landmarks", options->landmarks,
                     "Give each pair's match this many landmarks from the ground truth: reference "
                     "points spread over the template, as a user would click them (onto a view "
                     "or a holed target, among the points it holds)")
        ->check(non_negative_number());
    command->add_flag("--target-points", options->target.points,
                      "Give each pair's match its target as a point cloud, its vertices alone "
                      "(with --target-view, those of the view, as a depth camera gives them; the "
                      "errors are measured on the target mesh)");
    command->add_flag("--target-view", options->target.view,
                      "Give each pair's match only the target's faces that face a camera from a "
                      "random side (the same side for a pair in every run); the rows add the "
                      "error of the reference points it sees, mean_seen");
    command->add_flag("--target-normals", options->target.normals,
                      "Give the points of --target-points their normals (the target mesh's "
                      "vertex normals), as a scanner gives them");
    command
        ->add_option("--target-noise", options->target.noise,
                     "Move each point of --target-points, or else each vertex of the target, by "
                     "Gaussian noise of this σ, in mean edge lengths of the target (the same draw "
                     "for a pair in every run)")
        ->check(non_negative_number());
    command
        ->add_option("--target-holes", options->target.holes,
                     "Punch this many holes (discs of 0.03 diagonals) into each pair's target, "
                     "or into its view; the rows add mean_seen")
        ->check(number_in(0, 1000));
    command
        ->add_option("--target-fragments", options->target.fragments,
                     "Add this many loose fragments (discs of 0.02 diagonals copied off the "
                     "surface) to each pair's target, as the stray pieces of a scan")
        ->check(number_in(0, 1000));
    command->add_flag("--target-ragged", options->target.ragged,
                      "Make the target's boundary ragged (each face at it dropped with probability "
                      "1/2), as a scan's edge; with --target-view, --target-holes or "
                      "--target-out-of-frame");
    command
        ->add_option("--target-out-of-frame", options->target.out_of_frame,
                     "Cut off this share of each pair's target's extent along a random "
                     "direction, as a part beyond a scanner's frame (0.15 of a standing body's "
                     "height takes the feet); the rows add mean_seen")
        ->check(number_in(0.0, 0.9));
    command->add_flag("--json", options->json, "Print the summary as JSON instead of tables");
    command
        ->add_option("--method", options->method,
                     "match: the matcher (its options below); spectral-map: the intrinsic vertex "
                     "map alone (orientation-aware functional map and ZoomOut), the matcher's "
                     "first stage")
        ->check(CLI::IsMember({"match", "spectral-map"}))
        ->capture_default_str();
    add_prior_flag(*command, options->flags);
    add_match_flags(*command, options->flags);
    command->callback([options] { run_benchmark(*options); });
}

}  // namespace genflow::cli
