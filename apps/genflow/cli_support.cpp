// SPDX-License-Identifier: MIT
#include "cli_support.h"

#include <iostream>

#include "genflow/exceptions.h"
#include "genflow/io/read_mesh.h"

namespace genflow::cli {

LoadedMesh load_mesh(const std::filesystem::path& path) {
    LoadedMesh loaded;
    loaded.path = path;
    loaded.mesh = read_mesh(path, &loaded.read_warnings);
    loaded.report = validate(loaded.mesh);
    if (!loaded.report.ok()) {
        throw IoError(path.string() + ": " + loaded.report.first_error());
    }
    return loaded;
}

void print_warnings(const LoadedMesh& loaded) {
    for (const auto& warning : loaded.read_warnings) {
        std::cerr << "warning: " << warning << '\n';
    }
    for (const auto& issue : loaded.report.issues) {
        if (issue.severity == Severity::Warning) {
            std::cerr << "warning: " << loaded.path.string() << ": " << issue.message << '\n';
        }
    }
}

}  // namespace genflow::cli
