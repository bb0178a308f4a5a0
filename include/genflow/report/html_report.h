// SPDX-License-Identifier: MIT
// One self-contained HTML page that shows a run's meshes in a WebGL view, its traces as plots
// and its numbers as tables. Everything it shows is inside the file (three.js included), so it
// opens offline in any browser and can be mailed or archived as one file.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "genflow/io/vertex_attributes.h"
#include "genflow/mesh.h"

namespace genflow {

/// A mesh the report's view draws, with the values per vertex it can be coloured by.
struct ReportMesh {
    std::string name;             ///< its label in the view ("template", "target", "result")
    TriangleMesh mesh;            ///< a mesh without faces is drawn as points
    VertexAttributes attributes;  ///< colours offered as "own colours"; scalars as colourings
    bool shown = true;            ///< drawn when the page opens (a checkbox toggles it)
};

/// One line of a plot: y at x = first_x, first_x + 1, ...
struct ReportSeries {
    std::string name;
    double first_x = 0;
    std::vector<double> y;
};

/// A line plot, drawn as SVG (no script needed to see it).
struct ReportPlot {
    std::string title;
    std::string x_label;
    std::string y_label;
    std::vector<ReportSeries> series;
    bool log_y = true;  ///< a logarithmic y axis when every value is positive
};

/// A table of text cells.
struct ReportTable {
    std::string title;
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
};

/// A run as a report shows it.
struct Report {
    std::string title;         ///< the page's heading ("genflow match")
    std::string command_line;  ///< as typed, shown verbatim
    std::vector<ReportMesh> meshes;
    /// The top of each colouring's scale by its scalar's name; a colouring not listed runs up to
    /// the largest value of its scalar over all meshes.
    std::vector<std::pair<std::string, double>> color_scales;
    std::string default_coloring;  ///< a scalar's name, "own colours" or "" (plain)
    std::vector<ReportPlot> plots;
    std::vector<ReportTable> tables;
    std::string details;  ///< preformatted text at the end (e.g. the JSON summary)
};

/// The page of `report`: HTML5 with the scripts, style, meshes (base64) and plots inline. Text is
/// escaped; nothing is fetched when it is viewed.
/// \throws InvalidInput for a mesh that is not valid (require_valid_mesh()) or attributes whose
///         rows do not match its vertices.
[[nodiscard]] std::string html_report(const Report& report);

/// Writes html_report(report) to `path` atomically (write_file_atomically()).
/// \throws InvalidInput as html_report(); OutputError when the file cannot be written.
void write_html_report(const std::filesystem::path& path, const Report& report);

}  // namespace genflow
