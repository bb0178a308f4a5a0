// SPDX-License-Identifier: MIT
// genflow transfer SOURCE TARGET CORRESPONDENCE -o OUT: a template's per-vertex attributes
// (colours, labels, values) carried to the target a match put it on, through the match's
// correspondence file.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "cli_support.h"
#include "commands.h"
#include "genflow/exceptions.h"
#include "genflow/io/read_correspondences.h"
#include "genflow/matching/carry_attributes.h"

namespace genflow::cli {

namespace {

struct TransferOptions {
    std::string source;
    std::string target;
    std::string correspondence;
    std::string output;
};

// The target's own attributes, and those carried; a carried one replaces the target's of the
// same kind or name, with a warning.
VertexAttributes merged(const LoadedMesh& target, VertexAttributes carried) {
    const auto replaced = [&](const std::string& what) {
        std::cerr << "warning: " << printable(target.path.string()) << ": its " << what
                  << " are replaced by the source's\n";
    };
    VertexAttributes result = target.attributes;
    if (carried.colors.rows() > 0) {
        if (result.colors.rows() > 0) {
            replaced("vertex colours");
        }
        result.colors = std::move(carried.colors);
    }
    if (carried.uvs.rows() > 0) {
        if (result.uvs.rows() > 0 || result.corner_uv_faces.rows() > 0) {
            replaced("texture coordinates");
        }
        result.uvs = std::move(carried.uvs);
        result.corner_uvs.resize(0, 2);
        result.corner_uv_faces.resize(0, 3);
    }
    for (auto& [name, values] : carried.scalars) {
        std::erase_if(result.scalars, [&, &name = name](const auto& own) {
            const bool same = own.first == name;
            if (same) {
                replaced("values '" + printable(name) + "'");
            }
            return same;
        });
        result.scalars.emplace_back(name, std::move(values));
    }
    return result;
}

// "vertex colours, values and texture coordinates", as many as the source has.
std::string carried_words(const VertexAttributes& given) {
    std::vector<std::string> kinds;
    if (given.colors.rows() > 0) {
        kinds.emplace_back("colours");
    }
    if (!given.scalars.empty()) {
        kinds.emplace_back("values");
    }
    if (given.uvs.rows() > 0 || given.corner_uv_faces.rows() > 0) {
        kinds.emplace_back("texture coordinates");
    }
    std::string words = "vertex";
    for (std::size_t k = 0; k < kinds.size(); ++k) {
        words += (k == 0 ? " " : k + 1 == kinds.size() ? " and " : ", ") + kinds[k];
    }
    return words;
}

void run_transfer(const TransferOptions& options) {
    check_mesh_output(options.output);
    const LoadedMesh source = load_mesh(options.source);
    const LoadedMesh target = load_mesh(options.target);
    print_warnings(source);
    print_warnings(target);
    const VertexAttributes& given = source.attributes;
    if (given.colors.rows() == 0 && given.scalars.empty() && given.uvs.rows() == 0 &&
        given.corner_uv_faces.rows() == 0) {
        throw IoError(options.source +
                      ": no vertex colours, values or texture coordinates to transfer");
    }
    const std::vector<SurfacePoint> correspondence =
        read_correspondences(options.correspondence, target.mesh, source.mesh.V.rows());
    VertexAttributes carried =
        carry_attributes(source.mesh, source.attributes, target.mesh, correspondence);
    write_mesh_with(options.output, target.mesh, merged(target, std::move(carried)), false);
    std::printf("transfer: %s's %s onto the %ld vertices of %s; wrote %s\n",
                printable(options.source).c_str(), carried_words(given).c_str(),
                static_cast<long>(target.mesh.V.rows()), printable(options.target).c_str(),
                printable(options.output).c_str());
}

}  // namespace

void register_transfer_command(CLI::App& app) {
    auto options = std::make_shared<TransferOptions>();
    auto* command = app.add_subcommand(
        "transfer",
        "Carry a template's per-vertex colours, values and texture coordinates (labels taken "
        "from the nearest corner, others interpolated) to the target a match put it on, through "
        "the match's "
        "--correspondence file");
    command->add_option("source", options->source, "The template, with its vertex attributes")
        ->required();
    command->add_option("target", options->target, "The target it was matched onto")->required();
    command
        ->add_option("correspondence", options->correspondence,
                     "The correspondence file of that match (genflow match --correspondence)")
        ->required();
    command->add_option("-o,--output", options->output, "The target with the attributes")
        ->required();
    command->callback([options] { run_transfer(*options); });
}

}  // namespace genflow::cli
