// SPDX-License-Identifier: MIT
#include "reports.h"

#include <cstdio>

#include "cli_support.h"
#include "genflow/exceptions.h"
#include "genflow/io/atomic_file.h"

namespace genflow::cli {

namespace {

std::string& stored_command_line() {
    static std::string line;
    return line;
}

// A word as a POSIX shell reads it back: as it is when it holds only safe characters, else in
// single quotes (a quote inside written '\'').
std::string shell_word(const std::string& word) {
    const bool safe = !word.empty() && word.find_first_not_of(
                                           "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                           "0123456789_-+=.,/:@%") == std::string::npos;
    if (safe) {
        return word;
    }
    std::string quoted = "'";
    for (const char c : word) {
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    return quoted + "'";
}

// The last part of a path, for a title (the command line shows it whole).
std::string file_name(const std::string& path) {
    return std::filesystem::path(path).filename().string();
}

std::string text_of(const nlohmann::json& value) {
    if (value.is_string()) {
        return value.get<std::string>();
    }
    if (value.is_number_float()) {
        char text[32];
        std::snprintf(text, sizeof text, "%.6g", value.get<double>());
        return text;
    }
    return value.dump();
}

void add_rows(const nlohmann::json& object, const std::string& prefix, ReportTable& table) {
    for (const auto& [key, value] : object.items()) {
        if (value.is_object()) {
            add_rows(value, prefix + key + ".", table);
        } else if (!value.is_array()) {
            table.rows.push_back({prefix + key, text_of(value)});
        }
    }
}

// The distance of each vertex of `mesh` to `other`'s surface, as a value to colour it by.
VertexAttributes distance_to(const TriangleMesh& mesh, const TriangleMesh& other) {
    VertexAttributes attributes;
    attributes.scalars = result_values(mesh, other, nullptr);
    return attributes;
}

ReportPlot energy_plot(const MatchResult& result) {
    ReportPlot plot{
        "Pseudo-Hausdorff distance per step", "step (levels one after another)", "d_H", {}, true};
    double first = 0;
    for (std::size_t l = 0; l < result.levels.size(); ++l) {
        const MatchLevel& level = result.levels[l];
        plot.series.push_back({"level " + std::to_string(l + 1) + " (" +
                                   std::to_string(level.template_vertices) + " vertices)",
                               first, level.energy});
        first += static_cast<double>(level.energy.size());
    }
    return plot;
}

ReportTable levels_table(const MatchResult& result) {
    ReportTable table{"Levels",
                      {"level", "template vertices", "target vertices", "steps", "status",
                       "d_H start", "d_H end", "seconds"},
                      {}};
    for (std::size_t l = 0; l < result.levels.size(); ++l) {
        const MatchLevel& level = result.levels[l];
        table.rows.push_back({std::to_string(l + 1), std::to_string(level.template_vertices),
                              std::to_string(level.target_vertices),
                              std::to_string(level.iterations), to_string(level.status),
                              text_of(level.energy_start), text_of(level.energy_end),
                              text_of(level.seconds)});
    }
    return table;
}

ReportTable stages_table(const nlohmann::json& stages) {
    ReportTable table{"Error after each stage (mean, over the ground truth's diagonal)",
                      {"level", "stage", "vertices", "mean error"},
                      {}};
    for (const nlohmann::json& stage : stages) {
        table.rows.push_back({text_of(stage["level"]), text_of(stage["stage"]),
                              text_of(stage["vertices"]), text_of(stage["mean"])});
    }
    return table;
}

}  // namespace

void set_command_line(int argc, char** argv) {
    std::string line;
    for (int i = 0; i < argc; ++i) {
        line += (i == 0 ? "" : " ") + shell_word(i == 0 ? std::string("genflow") : argv[i]);
    }
    stored_command_line() = line;
}

const std::string& command_line() {
    return stored_command_line();
}

void check_report_output(const std::string& path) {
    if (!has_extension(path, ".html") && !has_extension(path, ".htm")) {
        throw IoError(path + ": a report is an HTML page (expected a name ending in .html)");
    }
    check_output_path(path);
}

ReportTable summary_table(const nlohmann::json& summary) {
    ReportTable table{"Summary", {"name", "value"}, {}};
    add_rows(summary, "", table);
    return table;
}

Report match_report(const MatchJob& job, const MatchResult& result, const VertexAttributes& values,
                    const nlohmann::json& summary) {
    Report report;
    report.title =
        "genflow match: " + file_name(job.template_name) + " onto " + file_name(job.target_name);
    report.command_line = stored_command_line();
    report.meshes = {{"template", job.template_mesh, job.template_attributes, true},
                     {"target", job.target, distance_to(job.target, result.deformed), true},
                     {"result", result.deformed, values, true}};
    report.default_coloring = job.ground_truth ? "error" : "distance";
    report.plots = {energy_plot(result)};
    report.tables = {summary_table(summary), levels_table(result)};
    if (job.ground_truth) {
        report.tables.push_back(stages_table(summary["stages"]));
    }
    report.details = summary.dump(2);
    return report;
}

Report smooth_report(const TriangleMesh& input, const FlowResult& result,
                     const nlohmann::json& summary) {
    Report report;
    report.title = "genflow smooth: " + file_name(summary["input"].get<std::string>());
    report.command_line = stored_command_line();
    VertexAttributes moved;
    moved.scalars.emplace_back("displacement", (result.mesh.V - input.V).rowwise().norm());
    report.meshes = {{"input", input, {}, true}, {"smoothed", result.mesh, moved, true}};
    report.default_coloring = "";  // plain: the shading shows what smoothing changed
    report.plots = {{"Energy per step", "step", "energy", {{"energy", 0, result.energy}}, true}};
    report.tables = {summary_table(summary)};
    report.details = summary.dump(2);
    return report;
}

Report distance_report(const TriangleMesh& a, const TriangleMesh& b, double scale_top,
                       const nlohmann::json& summary) {
    Report report;
    report.title = "genflow distance: " + file_name(summary["a"].get<std::string>()) + " and " +
                   file_name(summary["b"].get<std::string>());
    report.command_line = stored_command_line();
    report.meshes = {{"A", a, distance_to(a, b), true}, {"B", b, distance_to(b, a), true}};
    report.color_scales = {{"distance", scale_top}};
    report.default_coloring = "distance";
    report.tables = {summary_table(summary)};
    report.details = summary.dump(2);
    return report;
}

}  // namespace genflow::cli
