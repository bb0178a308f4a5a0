// SPDX-License-Identifier: MIT
// genflow demo [--output-dir DIR]: the built-in default job. It needs no input: it generates a
// noisy torus, writes it, reads it back the way every input is read, and reports on it.
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "genflow/exceptions.h"
#include "genflow/io/write_mesh.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"
#include "mesh_summary.h"

namespace genflow::cli {

namespace {

struct DemoOptions {
    std::string output_dir = "genflow-demo";
};

void run_demo(const DemoOptions& options) {
    const std::filesystem::path directory(options.output_dir);
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (error) {
        throw IoError(directory.string() + ": cannot create directory (" + error.message() + ")");
    }
    TriangleMesh torus = make_torus(96, 48, 1.0, 0.4);
    torus = add_noise(std::move(torus), 0.1 * mean_edge_length(torus), 20070704);
    const auto path = directory / "torus_noisy.ply";
    write_mesh(path, torus);
    const LoadedMesh loaded = load_mesh(path);
    print_warnings(loaded);
    std::cout << "genflow demo: generated a noisy torus and wrote " << path.string() << '\n'
              << mesh_summary_text(loaded);
}

}  // namespace

void register_demo_command(CLI::App& app) {
    auto options = std::make_shared<DemoOptions>();
    auto* command = app.add_subcommand(
        "demo",
        "Run the built-in default job on a mesh genflow generates itself (no input "
        "needed); writes its results to --output-dir");
    command->add_option("--output-dir", options->output_dir, "Directory for the results")
        ->capture_default_str();
    command->callback([options] { run_demo(*options); });
}

}  // namespace genflow::cli
