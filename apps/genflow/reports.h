// SPDX-License-Identifier: MIT
// --report FILE of match, smooth and distance: what each command shows of its run in an HTML
// report (genflow/report/html_report.h).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "genflow/flows/flow.h"
#include "genflow/matching/match.h"
#include "genflow/report/html_report.h"
#include "match_job.h"

namespace genflow::cli {

/// Remembers the command line as typed, for the reports to show (called once by main()).
void set_command_line(int argc, char** argv);

/// The command line as set_command_line() remembered it, each word shell-quoted as needed.
[[nodiscard]] const std::string& command_line();

/// Checks --report before any work: a name ending in .html or .htm, in a place it can be
/// written (check_output_path()); throws IoError naming the path otherwise.
void check_report_output(const std::string& path);

/// A table of the summary's numbers, words and flags, one row each (nested names joined with
/// '.'; lists left to the JSON at the end of the report).
[[nodiscard]] ReportTable summary_table(const nlohmann::json& summary);

/// A match: the template, the target (with its vertices' distance to the result) and the
/// deformed template with `values` (distance and, with a ground truth, error; coloured by the
/// error where there is one), d_H per step of every level, the levels and stages, the summary.
[[nodiscard]] Report match_report(const MatchJob& job, const MatchResult& result,
                                  const VertexAttributes& values, const nlohmann::json& summary);

/// A smoothing: the input and the smoothed mesh (plain, or coloured by how far each vertex
/// moved), the flow's energy per step, the summary.
[[nodiscard]] Report smooth_report(const TriangleMesh& input, const FlowResult& result,
                                   const nlohmann::json& summary);

/// Two meshes' distances: A coloured by its distance to B and B by its distance to A, on one
/// scale from 0 to `scale_top`, and the summary.
[[nodiscard]] Report distance_report(const TriangleMesh& a, const TriangleMesh& b, double scale_top,
                                     const nlohmann::json& summary);

}  // namespace genflow::cli
