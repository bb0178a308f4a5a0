// SPDX-License-Identifier: MIT
// Each subcommand registers itself on the CLI11 app; its callback does the work.
#pragma once

#include <CLI/CLI.hpp>

namespace genflow::cli {

void register_info_command(CLI::App& app);
void register_demo_command(CLI::App& app);
void register_smooth_command(CLI::App& app);
void register_distance_command(CLI::App& app);
void register_match_command(CLI::App& app);
void register_eval_command(CLI::App& app);
void register_benchmark_command(CLI::App& app);
void register_transfer_command(CLI::App& app);
void register_batch_command(CLI::App& app);

}  // namespace genflow::cli
