// SPDX-License-Identifier: MIT
// Checks the exact surface distances on every pair of a pairs.json (template against the
// ground-truth target, both directions) against dense surface sampling, and prints a Markdown
// table with the times. Usage: distance_check_table [PAIRS.json] (default
// $GENFLOW_DATA/pairs.json). Exit status 1 if a pair breaks a stated bound.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "genflow/io/read_mesh.h"
#include "genflow/spatial/surface_distance.h"
#include "support/reference_distances.h"

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// sampled ≤ exact ≤ upper bound, exact ≤ sampled + radius, means within their bounds.
bool consistent(const genflow::OneSidedDistance& exact, const genflow::test::SampledDistance& s) {
    const double slack = 1e-9 * (1 + exact.hausdorff);
    return s.max <= exact.hausdorff_upper_bound + slack &&
           exact.hausdorff <= s.max + s.radius + slack &&
           std::abs(exact.mean - s.mean) <= exact.mean_error_bound + s.radius + slack;
}

}  // namespace

int main(int argc, char** argv) {
    const char* data = std::getenv("GENFLOW_DATA");
    const std::filesystem::path root = data != nullptr ? data : "../shared/data";
    const std::filesystem::path pairs_file = argc > 1 ? argv[1] : (root / "pairs.json").string();
    std::ifstream stream(pairs_file);
    if (!stream) {
        std::fprintf(stderr, "distance_check_table: cannot open %s\n", pairs_file.c_str());
        return 2;
    }
    const nlohmann::json pairs = nlohmann::json::parse(stream);
    const std::filesystem::path base = pairs_file.parent_path();

    std::printf(
        "| pair | H(A→B) exact | sampled max + radius | H(B→A) exact | sampled max + radius | "
        "mean A→B exact / sampled | exact time | sampling time | bounds hold |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
    bool all_hold = true;
    for (const auto& pair : pairs) {
        const auto name = pair.at("name").get<std::string>();
        const genflow::TriangleMesh A =
            genflow::read_mesh(base / pair.at("template").get<std::string>());
        const genflow::TriangleMesh B =
            genflow::read_mesh(base / pair.at("target_ground_truth").get<std::string>());
        auto start = std::chrono::steady_clock::now();
        const genflow::SurfaceDistances exact = genflow::surface_distances(A, B);
        const double exact_time = seconds_since(start);
        start = std::chrono::steady_clock::now();
        const auto ab = genflow::test::sampled_distance(A, B, 4);
        const auto ba = genflow::test::sampled_distance(B, A, 4);
        const double sampling_time = seconds_since(start);
        const bool hold = consistent(exact.a_to_b, ab) && consistent(exact.b_to_a, ba);
        all_hold = all_hold && hold;
        std::printf(
            "| %s | %.4f | %.4f + %.4f | %.4f | %.4f + %.4f | %.4f / %.4f | %.2f s | %.2f s | %s "
            "|\n",
            name.c_str(), exact.a_to_b.hausdorff, ab.max, ab.radius, exact.b_to_a.hausdorff, ba.max,
            ba.radius, exact.a_to_b.mean, ab.mean, exact_time, sampling_time, hold ? "yes" : "NO");
        std::fflush(stdout);
    }
    return all_hold ? 0 : 1;
}
