// SPDX-License-Identifier: MIT
#include "genflow/report/html_report.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>

#include "genflow/exceptions.h"
#include "genflow/io/atomic_file.h"
#include "genflow/io/color_map.h"
#include "genflow/version.h"
#include "operators/triangle.h"
#include "report/base64.h"
#include "report/html_escape.h"
#include "report/report_assets.h"
#include "report/svg_plot.h"

namespace genflow {

namespace {

// The colouring of a mesh's own vertex colours, beside those of its values.
constexpr const char* kOwnColors = "own colours";

void check_mesh(const ReportMesh& shown) {
    const TriangleMesh& mesh = shown.mesh;
    const std::string name = "html_report: mesh \"" + shown.name + "\"";
    if (mesh.F.rows() == 0 || mesh.F.minCoeff() < 0 || mesh.F.maxCoeff() >= mesh.V.rows()) {
        throw InvalidInput(name + " needs faces whose indices lie among its vertices");
    }
    if (!detail::all_finite(mesh.V)) {
        throw InvalidInput(name + " has non-finite coordinates");
    }
    const VertexAttributes& attributes = shown.attributes;
    bool rows_match = attributes.colors.rows() == 0 || attributes.colors.rows() == mesh.V.rows();
    for (const auto& [scalar, values] : attributes.scalars) {
        rows_match = rows_match && values.size() == mesh.V.rows();
    }
    if (!rows_match) {
        throw InvalidInput(name + " has attributes whose rows are not its vertices");
    }
}

// Little-endian 32-bit words, as the view script reads them on any platform.
void append_word(std::string& bytes, std::uint32_t word) {
    for (int shift = 0; shift < 32; shift += 8) {
        bytes += static_cast<char>((word >> shift) & 0xFFU);
    }
}

std::string float_array(const Eigen::MatrixX3d& V) {
    std::string bytes;
    bytes.reserve(static_cast<std::size_t>(V.size()) * 4);
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const auto value = static_cast<float>(V(i, c));
            std::uint32_t word = 0;
            std::memcpy(&word, &value, sizeof word);
            append_word(bytes, word);
        }
    }
    return detail::base64(bytes);
}

std::string index_array(const Eigen::MatrixX3i& F) {
    std::string bytes;
    bytes.reserve(static_cast<std::size_t>(F.size()) * 4);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            append_word(bytes, static_cast<std::uint32_t>(F(f, c)));
        }
    }
    return detail::base64(bytes);
}

std::string color_array(const VertexColors& colors) {
    return detail::base64(
        {reinterpret_cast<const char*>(colors.data()), static_cast<std::size_t>(colors.size())});
}

// The colourings the view offers: the meshes' own colours, then each scalar by name, over
// [0, top] with top from Report::color_scales or the scalar's largest value.
struct Coloring {
    std::string name;
    double top = 0;  // 0 for own colours
};

std::vector<Coloring> colorings_of(const Report& report) {
    std::vector<Coloring> colorings;
    const auto has_own = [](const ReportMesh& m) { return m.attributes.colors.rows() > 0; };
    if (std::any_of(report.meshes.begin(), report.meshes.end(), has_own)) {
        colorings.push_back({kOwnColors, 0});
    }
    for (const ReportMesh& mesh : report.meshes) {
        for (const auto& [name, values] : mesh.attributes.scalars) {
            auto known = std::find_if(colorings.begin(), colorings.end(),
                                      [&](const Coloring& c) { return c.name == name; });
            if (known == colorings.end()) {
                colorings.push_back({name, 0});
                known = colorings.end() - 1;
            }
            for (const double value : values) {
                known->top = std::isfinite(value) ? std::max(known->top, value) : known->top;
            }
        }
    }
    for (Coloring& coloring : colorings) {
        for (const auto& [name, top] : report.color_scales) {
            coloring.top = name == coloring.name && top > 0 ? top : coloring.top;
        }
        if (coloring.name != kOwnColors && !(coloring.top > 0)) {
            coloring.top = 1;  // all values 0 (or none): any scale shows them as its bottom
        }
    }
    return colorings;
}

// The viridis scale as a CSS gradient for the legend.
std::string gradient() {
    constexpr int kStops = 9;
    const VertexColors colors = viridis_colors(Eigen::VectorXd::LinSpaced(kStops, 0, 1), 0, 1);
    std::string css = "linear-gradient(to right";
    for (int i = 0; i < kStops; ++i) {
        css += ", rgb(" + std::to_string(colors(i, 0)) + "," + std::to_string(colors(i, 1)) + "," +
               std::to_string(colors(i, 2)) + ") " + std::to_string(100 * i / (kStops - 1)) + "%";
    }
    return css + ")";
}

nlohmann::json mesh_data(const ReportMesh& shown, const std::vector<Coloring>& colorings) {
    nlohmann::json colors = nlohmann::json::object();
    for (const Coloring& coloring : colorings) {
        if (coloring.name == kOwnColors && shown.attributes.colors.rows() > 0) {
            colors[coloring.name] = color_array(shown.attributes.colors);
        }
        for (const auto& [name, values] : shown.attributes.scalars) {
            if (name == coloring.name) {
                colors[name] = color_array(viridis_colors(values, 0, coloring.top));
            }
        }
    }
    return {{"name", shown.name},
            {"shown", shown.shown},
            {"positions", float_array(shown.mesh.V)},
            {"indices", index_array(shown.mesh.F)},
            {"colorings", colors}};
}

std::string number_text(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

// The view's data as JSON inside a <script> element, every '<' written \u003c (the same string
// to JSON): no text can then close the element or open a comment in it.
std::string view_data(const Report& report) {
    const std::vector<Coloring> colorings = colorings_of(report);
    nlohmann::json data;
    data["meshes"] = nlohmann::json::array();
    for (const ReportMesh& mesh : report.meshes) {
        data["meshes"].push_back(mesh_data(mesh, colorings));
    }
    data["colorings"] = nlohmann::json::array();
    const std::string scale = gradient();
    for (const Coloring& coloring : colorings) {
        nlohmann::json entry{{"name", coloring.name}};
        if (coloring.name != kOwnColors) {
            entry["top"] = coloring.top;
            entry["top_text"] = number_text(coloring.top);
            entry["gradient"] = scale;
        }
        data["colorings"].push_back(entry);
    }
    data["default_coloring"] = report.default_coloring;
    const std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    std::string escaped;
    escaped.reserve(text.size());
    for (const char c : text) {
        escaped += c == '<' ? std::string("\\u003c") : std::string(1, c);
    }
    return escaped;
}

std::string head(const Report& report) {
    return "<!doctype html>\n<html lang='en'>\n<head>\n<meta charset='utf-8'>\n"
           "<meta name='viewport' content='width=device-width, initial-scale=1'>\n"
           "<meta name='generator' content='genflow " +
           std::string(kVersion) + "'>\n<title>" + detail::escape_html(report.title) +
           "</title>\n<style>\n" + std::string(detail::report_css()) + "</style>\n</head>\n";
}

std::string view_section(const Report& report) {
    std::string html = "<h1>" + detail::escape_html(report.title) + "</h1>\n";
    html += "<p class='meta'>genflow " + std::string(kVersion) + " &middot; <code>" +
            detail::escape_html(report.command_line) + "</code></p>\n";
    if (report.meshes.empty()) {
        return html;
    }
    html +=
        "<div class='controls'><span id='mesh-toggles'></span>"
        "<label>colour by <select id='coloring'></select></label>"
        "<span><label><input type='radio' name='layout' value='side' checked> side by "
        "side</label> <label><input type='radio' name='layout' value='overlay'> "
        "overlaid</label></span>"
        "<span id='legend' hidden><span id='legend-name'></span> 0 <span "
        "id='legend-bar'></span> <span id='legend-top'></span></span></div>\n"
        "<p id='viewer-error' hidden></p>\n<div id='viewer'></div>\n"
        "<p class='meta'>Drag to turn, right-drag to move, scroll to zoom; "
        "<a href='#view'>the view alone</a>.</p>\n"
        "<noscript><p>The view needs JavaScript; the plots and tables below do not.</p>"
        "</noscript>\n";
    return html;
}

std::string plots_section(const Report& report) {
    std::string html;
    for (const ReportPlot& plot : report.plots) {
        html += "<h2>" + detail::escape_html(plot.title) + "</h2>\n" + detail::svg_line_plot(plot) +
                "\n";
    }
    return html;
}

bool looks_numeric(const std::string& cell) {
    double value = 0;
    char rest = 0;
    return std::sscanf(cell.c_str(), "%lf%c", &value, &rest) == 1;
}

std::string tables_section(const Report& report) {
    std::string html;
    for (const ReportTable& table : report.tables) {
        html += "<h2>" + detail::escape_html(table.title) + "</h2>\n<table>\n<tr>";
        for (const std::string& cell : table.header) {
            html += "<th>" + detail::escape_html(cell) + "</th>";
        }
        html += "</tr>\n";
        for (const auto& row : table.rows) {
            html += "<tr>";
            for (const std::string& cell : row) {
                html += (looks_numeric(cell) ? "<td class='number'>" : "<td>") +
                        detail::escape_html(cell) + "</td>";
            }
            html += "</tr>\n";
        }
        html += "</table>\n";
    }
    if (!report.details.empty()) {
        html += "<h2>Details</h2>\n<pre>" + detail::escape_html(report.details) + "</pre>\n";
    }
    return html;
}

std::string scripts(const Report& report) {
    if (report.meshes.empty()) {
        return "";
    }
    return "<script type='application/json' id='genflow-report-data'>" + view_data(report) +
           "</script>\n"
           "<!-- three.js r111 and its OrbitControls (MIT licence, copyright 2010-2019 three.js "
           "authors), as Debian's libjs-three ships them -->\n<script>\n" +
           std::string(detail::three_js()) + "\n</script>\n<script>\n" +
           std::string(detail::orbit_controls_js()) + "\n</script>\n<script>\n" +
           std::string(detail::viewer_js()) + "\n</script>\n";
}

}  // namespace

std::string html_report(const Report& report) {
    for (const ReportMesh& mesh : report.meshes) {
        check_mesh(mesh);
    }
    return head(report) + "<body>\n" + view_section(report) + plots_section(report) +
           tables_section(report) + scripts(report) + "</body>\n</html>\n";
}

void write_html_report(const std::filesystem::path& path, const Report& report) {
    write_file_atomically(path, html_report(report));
}

}  // namespace genflow
