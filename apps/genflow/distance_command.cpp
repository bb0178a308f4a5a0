// SPDX-License-Identifier: MIT
// genflow distance A B: exact surface distances (Hausdorff, mean, RMS, with error bounds) and
// the pseudo-Hausdorff value d_H of the paper's Appendix A.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "cli_support.h"
#include "commands.h"
#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/io/atomic_file.h"
#include "genflow/io/color_map.h"
#include "genflow/io/write_mesh.h"
#include "genflow/matching/correspondence.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/spatial/surface_distance.h"
#include "mesh_summary.h"
#include "number_checks.h"
#include "reports.h"

namespace genflow::cli {

namespace {

struct DistanceOptions {
    std::string a;
    std::string b;
    double alpha = 8;
    double epsilon = 0;   // 0: the mean edge length of B
    std::string colored;  // where A goes with its distance to B per vertex; empty: nowhere
    double scale = 0;     // the colour scale's top; 0: the Hausdorff distance A → B
    std::string report;   // an HTML page showing both meshes coloured; empty: none
    bool json = false;
    bool hausdorff_only = false;  // no mean, RMS or pseudo-Hausdorff value
};

// The colour scale of --colored: [0, top].
struct ColorScale {
    double top = 0;
    const char* meaning = "";
};

// A with each vertex's distance to the surface of B: a "distance" property and its colour on
// viridis over `scale`.
void write_colored(const std::string& path, const TriangleMesh& a, const TriangleMesh& b,
                   const ColorScale& scale) {
    VertexAttributes attributes;
    attributes.scalars = result_values(a, b, nullptr);
    attributes.colors = viridis_colors(attributes.scalars.front().second, 0, scale.top);
    write_mesh_with(path, a, attributes, false);
}

// The top of the colour scale: --scale, else the Hausdorff distance A → B (the largest of the
// distances coloured), else, for A on B, the bounding-box diagonal.
ColorScale color_scale(const DistanceOptions& options, const SurfaceDistances& d, double diagonal) {
    if (options.scale > 0) {
        return {options.scale, "--scale"};
    }
    if (d.a_to_b.hausdorff > 0) {
        return {d.a_to_b.hausdorff, "the Hausdorff distance A -> B"};
    }
    return {diagonal, "the bounding-box diagonal (A lies on B)"};
}

nlohmann::json one_sided_json(const OneSidedDistance& d, bool with_mean) {
    nlohmann::json one_sided = {
        {"hausdorff", d.hausdorff},
        {"hausdorff_upper_bound", d.hausdorff_upper_bound},
        {"farthest_point", {d.farthest_point[0], d.farthest_point[1], d.farthest_point[2]}}};
    if (with_mean) {
        one_sided["mean"] = d.mean;
        one_sided["mean_error_bound"] = d.mean_error_bound;
        one_sided["rms"] = d.rms;
        one_sided["rms_error_bound"] = d.rms_error_bound;
    }
    return one_sided;
}

// What the distances are, as --json prints them.
nlohmann::json distance_summary(const DistanceOptions& options, const SurfaceDistances& d,
                                double diagonal, double epsilon, double d_H,
                                const ColorScale& scale) {
    const bool with_mean = !options.hausdorff_only;
    nlohmann::json summary = {
        {"a", options.a},
        {"b", options.b},
        {"hausdorff", d.hausdorff},
        {"hausdorff_upper_bound", d.hausdorff_upper_bound},
        {"a_to_b", one_sided_json(d.a_to_b, with_mean)},
        {"b_to_a", one_sided_json(d.b_to_a, with_mean)},
        {"bbox_diagonal", diagonal},
    };
    if (with_mean) {
        summary["mean"] = d.mean;
        summary["rms"] = d.rms;
        summary["pseudo_hausdorff"] = {
            {"value", d_H}, {"alpha", options.alpha}, {"epsilon", epsilon}};
    }
    if (!options.colored.empty()) {
        summary["colored"] = {{"file", options.colored},
                              {"property", "distance"},
                              {"color_map", "viridis"},
                              {"scale", {0.0, scale.top}}};
    }
    if (!options.report.empty()) {
        summary["report"] = options.report;
    }
    return summary;
}

// A line a direction and a symmetric one: the Hausdorff distance (with its bound), and the mean
// and RMS unless --hausdorff-only; then d_H.
void print_distances(const DistanceOptions& options, const SurfaceDistances& d,
                     const nlohmann::json& summary) {
    const bool with_mean = !options.hausdorff_only;
    const auto one_sided = [&](const std::string& from, const std::string& to,
                               const OneSidedDistance& side) {
        std::printf("%s -> %s: Hausdorff %.6g (<= %.6g)", from.c_str(), to.c_str(), side.hausdorff,
                    side.hausdorff_upper_bound);
        if (with_mean) {
            std::printf(", mean %.6g, rms %.6g", side.mean, side.rms);
        }
        std::printf("\n");
    };
    one_sided(options.a, options.b, d.a_to_b);
    one_sided(options.b, options.a, d.b_to_a);
    std::printf("symmetric: Hausdorff %.6g (%.4g%% of the bbox diagonal)", d.hausdorff,
                100 * d.hausdorff / summary["bbox_diagonal"].get<double>());
    if (with_mean) {
        std::printf(", mean %.6g, rms %.6g", d.mean, d.rms);
    }
    std::printf("\n");
    if (with_mean) {
        const nlohmann::json& pseudo = summary["pseudo_hausdorff"];
        std::printf("pseudo-Hausdorff d_H (alpha %g, epsilon %.6g): %.6g\n", options.alpha,
                    pseudo["epsilon"].get<double>(), pseudo["value"].get<double>());
    }
}

void print_outputs(const DistanceOptions& options, const ColorScale& scale) {
    if (!options.colored.empty()) {
        std::printf(
            "%s: A with its distance to B per vertex (property \"distance\"), coloured on "
            "viridis from 0 (dark purple) to %.6g (yellow; %s)\n",
            printable(options.colored).c_str(), scale.top, scale.meaning);
    }
    if (!options.report.empty()) {
        std::printf("%s: both meshes coloured by their distance, to look at in a browser\n",
                    printable(options.report).c_str());
    }
}

void print_distance_text(const DistanceOptions& options, const SurfaceDistances& d,
                         const nlohmann::json& summary, const ColorScale& scale) {
    print_distances(options, d, summary);
    print_outputs(options, scale);
}

void run_distance(const DistanceOptions& options) {
    if (!options.colored.empty()) {
        check_mesh_output(options.colored);
    }
    if (!options.report.empty()) {
        check_report_output(options.report);
    }
    const LoadedMesh a = load_mesh(options.a);
    const LoadedMesh b = load_mesh(options.b);
    if (!options.json) {
        print_warnings(a);
        print_warnings(b);
    }
    const SurfaceDistances d =
        surface_distances(a.mesh, b.mesh, {.mean_and_rms = !options.hausdorff_only});
    const double epsilon = options.epsilon > 0 ? options.epsilon : mean_edge_length(b.mesh);
    const double d_H =
        options.hausdorff_only
            ? 0.0
            : PseudoHausdorffEnergy(b.mesh, {.alpha = options.alpha, .epsilon = epsilon})
                  .value(a.mesh);
    const double diagonal = std::max(bounding_box_diagonal(a.mesh), bounding_box_diagonal(b.mesh));
    const ColorScale scale = color_scale(options, d, diagonal);
    const nlohmann::json summary = distance_summary(options, d, diagonal, epsilon, d_H, scale);
    OutputTransaction outputs;
    if (!options.colored.empty()) {
        write_colored(options.colored, a.mesh, b.mesh, scale);
    }
    if (!options.report.empty()) {
        // Both directions on one scale: --scale, else the symmetric Hausdorff distance (the
        // larger one-sided one).
        const double top = options.scale > 0 ? options.scale : d.hausdorff;
        write_html_report(options.report, distance_report(a.mesh, b.mesh, top, summary));
    }
    outputs.commit();
    if (options.json) {
        std::cout << summary.dump(2) << '\n';
        return;
    }
    print_distance_text(options, d, summary, scale);
}

}  // namespace

void register_distance_command(CLI::App& app) {
    auto options = std::make_shared<DistanceOptions>();
    auto* command = app.add_subcommand(
        "distance",
        "Exact surface-to-surface distances between two meshes (one-sided and symmetric "
        "Hausdorff with a proven bound, mean and RMS) and the pseudo-Hausdorff value");
    command->add_option("a", options->a, "First mesh")->required();
    command->add_option("b", options->b, "Second mesh")->required();
    command->add_option("--alpha", options->alpha, "Exponent α of the pseudo-Hausdorff distance")
        ->check(number_in(0.5, 1e6))
        ->capture_default_str();
    command
        ->add_option("--eps", options->epsilon,
                     "Its ε, a length (default: mean edge length of the second mesh)")
        ->check(positive_length());
    command->add_option("--colored", options->colored,
                        "Write A with its distance to B per vertex: a \"distance\" property (PLY) "
                        "and vertex colours on viridis (.ply, .obj, .off)");
    command
        ->add_option("--scale", options->scale,
                     "The distance coloured yellow (default: the Hausdorff distance A -> B), to "
                     "put several results on one scale")
        ->check(positive_length());
    command->add_option("--report", options->report,
                        "Write an HTML page showing A and B in a 3D view, each coloured by its "
                        "distance to the other, and the numbers (.html)");
    command->add_flag("--json", options->json, "Print one JSON object instead of text");
    command->add_flag("--hausdorff-only", options->hausdorff_only,
                      "The exact Hausdorff distances alone, without the mean and RMS quadrature "
                      "or the pseudo-Hausdorff value");
    command->callback([options] { run_distance(*options); });
}

}  // namespace genflow::cli
