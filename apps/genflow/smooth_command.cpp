// SPDX-License-Identifier: MIT
// genflow smooth IN OUT --method ...: the smoothing flows of genflow/smoothing/smoothing.h.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "frame_sink.h"
#include "genflow/exceptions.h"
#include "genflow/io/atomic_file.h"
#include "genflow/io/write_mesh.h"
#include "genflow/operators/area.h"
#include "genflow/operators/volume.h"
#include "genflow/smoothing/smoothing.h"
#include "mesh_summary.h"
#include "number_checks.h"
#include "progress_bar.h"
#include "reports.h"

namespace genflow::cli {

namespace {

struct SmoothCommandOptions {
    std::string input;
    std::string output;
    std::string method = "volume-fairing";
    SmoothingOptions smoothing;
    double lambda = 0;  // 0: unset (λ = dt)
    bool json = false;
    std::string frames;
    int frame_every = 1;
    std::string report;
};

// "+1.234%".
std::string signed_percent(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%+.3f%%", value);
    return text;
}

// The run in numbers: its flow, and the area and enclosed volume before and after (the change
// of volume only for a closed surface, whose volume means something).
nlohmann::json smooth_summary(const SmoothCommandOptions& options, const LoadedMesh& loaded,
                              const FlowResult& result) {
    const double volume_before = enclosed_volume(loaded.mesh);
    const double volume_after = enclosed_volume(result.mesh);
    const bool closed = loaded.report.closed() && volume_before != 0;
    const double volume_change =
        closed ? 100 * (std::abs(volume_after) - std::abs(volume_before)) / std::abs(volume_before)
               : 0;
    return {
        {"input", options.input},
        {"output", options.output},
        {"method", options.method},
        {"freeze_metric", options.smoothing.freeze_metric},
        {"status", to_string(result.status)},
        {"steps", result.steps},
        {"seconds", result.seconds},
        {"area_before", surface_area(loaded.mesh)},
        {"area_after", surface_area(result.mesh)},
        {"volume_before", volume_before},
        {"volume_after", volume_after},
        {"volume_change_percent", closed ? nlohmann::json(volume_change) : nlohmann::json(nullptr)},
        {"closed", loaded.report.closed()},
        {"energy_rose", result.energy_rose()},
        {"energy", result.energy},
    };
}

void print_smooth_text(const SmoothCommandOptions& options, const FlowResult& result,
                       const nlohmann::json& summary) {
    if (result.energy_rose()) {
        std::cerr << "warning: " << printable(options.input) << ": the flow's energy rose ("
                  << result.energy.front() << " -> " << result.energy.back()
                  << "): the time step is too large for this metric; try a smaller --dt"
                  << (options.method == "fairing" || options.method == "fairing2"
                          ? " or a larger --lambda"
                          : "")
                  << '\n';
    }
    const nlohmann::json& volume_change = summary["volume_change_percent"];
    const std::string volume_change_text =
        volume_change.is_null() ? " (open surface)"
                                : " (" + signed_percent(volume_change.get<double>()) + ")";
    std::printf(
        "smooth: %s, %d steps (%s) in %.2f s; area %.6g -> %.6g; volume %.6g -> %.6g%s; "
        "wrote %s\n",
        options.method.c_str(), result.steps, to_string(result.status), result.seconds,
        summary["area_before"].get<double>(), summary["area_after"].get<double>(),
        summary["volume_before"].get<double>(), summary["volume_after"].get<double>(),
        volume_change_text.c_str(), printable(options.output).c_str());
    if (!options.report.empty()) {
        std::printf("%s: the smoothing to look at in a browser\n",
                    printable(options.report).c_str());
    }
}

void run_smooth(SmoothCommandOptions options) {
    check_mesh_output(options.output);
    if (!options.report.empty()) {
        check_report_output(options.report);
    }
    const LoadedMesh loaded = load_mesh(options.input);
    if (!options.json) {
        print_warnings(loaded);
    }
    FrameSink frames(options.frames.empty() ? std::nullopt
                                            : std::optional<std::filesystem::path>(options.frames));
    frames.add(loaded.mesh, 0);
    if (options.lambda > 0) {
        options.smoothing.lambda = options.lambda;
    }
    ProgressBar bar("smooth", !options.json);
    options.smoothing.progress = [&](const FlowProgress& progress) {
        bar.update(progress.step, progress.max_steps, "E " + std::to_string(progress.energy));
        if (progress.step % options.frame_every == 0 || progress.step == progress.max_steps) {
            frames.add(*progress.mesh, progress.step);
        }
        return true;
    };
    const FlowResult result = smoothing_flow(options.method).run(loaded.mesh, options.smoothing);
    bar.finish();
    if (!result.ok()) {
        throw SolverError("smoothing failed after " + std::to_string(result.steps) + " steps (" +
                          to_string(result.status) + "): " + result.message);
    }
    const nlohmann::json summary = smooth_summary(options, loaded, result);
    // All or none, as a match's outputs.
    OutputTransaction outputs;
    const VertexAttributes carried = carried_attributes(loaded, options.json);
    write_mesh_with(options.output, result.mesh, carried, options.json);
    frames.finish(carried);
    if (!options.report.empty()) {
        write_html_report(options.report, smooth_report(loaded.mesh, result, summary));
    }
    outputs.commit();
    if (options.json) {
        std::cout << summary.dump(2) << '\n';
        return;
    }
    print_smooth_text(options, result, summary);
}

}  // namespace

void register_smooth_command(CLI::App& app) {
    auto options = std::make_shared<SmoothCommandOptions>();
    auto* command = app.add_subcommand(
        "smooth",
        "Smooth a mesh by a gradient flow of its area (mean-curvature flow, implicit "
        "fairing = H1 flow, H2 fairing, volume-controlled fairing) and write the result");
    command->add_option("input", options->input, "Input mesh (.obj, .ply, .off, .stl)")->required();
    command->add_option("output", options->output, "Output mesh (.obj, .ply, .off)")->required();
    std::vector<std::string> names;
    for (const SmoothingFlow& flow : smoothing_flows()) {
        names.emplace_back(flow.name);
    }
    command
        ->add_option("--method", options->method,
                     "mcf: explicit L2 flow of the area; fairing: H1 flow (implicit fairing); "
                     "fairing2: H2 flow; volume-fairing: implicit fairing in the "
                     "volume-controlled metric (does not shrink)")
        ->check(CLI::IsMember(names))
        ->capture_default_str();
    command
        ->add_option("--dt", options->smoothing.time_step,
                     "Time step in units of h² (h = mean edge length)")
        ->check(positive_number())
        ->capture_default_str();
    command->add_option("--steps", options->smoothing.steps, "Number of steps")
        ->check(non_negative_number())
        ->capture_default_str();
    command
        ->add_option("--lambda", options->lambda,
                     "fairing/fairing2: the Sobolev metric's λ in units of h² (default: = dt)")
        ->check(positive_number());
    command->add_option("--mu", options->smoothing.mu, "fairing2: weight of Δ² in units of h⁴")
        ->check(non_negative_number())
        ->capture_default_str();
    command
        ->add_option(
            "--volume-lambda", options->smoothing.volume_lambda,
            "volume-fairing: volume penalty in (0, 1]; volume loss ≈ this × that of fairing")
        ->check(number_in(1e-12, 1.0))
        ->capture_default_str();
    command->add_flag("--fix-boundary", options->smoothing.fix_boundary,
                      "Keep boundary vertices where they are");
    command->add_flag("--freeze-metric", options->smoothing.freeze_metric,
                      "Flow in the metric of the input at every step (fairing: one "
                      "factorization in all, a solve a step)");
    command->add_flag("--json", options->json, "Print a JSON summary instead of text");
    command->add_option("--frames", options->frames,
                        "Write the input and every k-th step to DIR/frame_NNNNN.ply (float PLY), "
                        "or as one animated glTF to a name ending in .glb");
    command->add_option("--frame-every", options->frame_every, "k for --frames")
        ->check(positive_number())
        ->capture_default_str();
    command->add_option("--report", options->report,
                        "Write an HTML page showing the smoothing: input and result in a 3D view "
                        "(plain or coloured by how far each vertex moved), the energy per step "
                        "(.html)");
    command->callback([options] { run_smooth(*options); });
}

}  // namespace genflow::cli
