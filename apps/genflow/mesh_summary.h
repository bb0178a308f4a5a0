// SPDX-License-Identifier: MIT
// The measurements `genflow info` reports, as text and as JSON.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.h"

namespace genflow::cli {

/// The JSON object of `genflow info --json` (schema in docs/cli.md).
nlohmann::json mesh_summary_json(const LoadedMesh& loaded);

/// The human-readable form of the same information, several lines.
std::string mesh_summary_text(const LoadedMesh& loaded);

}  // namespace genflow::cli
