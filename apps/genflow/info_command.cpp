// SPDX-License-Identifier: MIT
// genflow info MESH [--json]: counts, validation report and measurements of one mesh.
#include <iostream>
#include <memory>

#include "commands.h"
#include "mesh_summary.h"

namespace genflow::cli {

namespace {

struct InfoOptions {
    std::string mesh;
    bool json = false;
};

void run_info(const InfoOptions& options) {
    const LoadedMesh loaded = load_mesh(options.mesh);
    if (options.json) {
        std::cout << mesh_summary_json(loaded).dump(2) << '\n';
        return;
    }
    print_warnings(loaded);
    std::cout << mesh_summary_text(loaded);
}

}  // namespace

void register_info_command(CLI::App& app) {
    auto options = std::make_shared<InfoOptions>();
    auto* command = app.add_subcommand(
        "info",
        "Print counts, the validation report (non-finite coordinates, bad or duplicate "
        "faces, non-manifold edges and vertices, boundaries, orientation), area, volume, "
        "bounding box and genus of a mesh");
    command->add_option("mesh", options->mesh, "Mesh file (.obj, .ply, .off, .stl)")->required();
    command->add_flag("--json", options->json,
                      "Print one JSON object on stdout instead of text (schema in docs/cli.md); "
                      "warnings go into it instead of stderr");
    command->callback([options] { run_info(*options); });
}

}  // namespace genflow::cli
