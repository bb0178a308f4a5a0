// SPDX-License-Identifier: MIT
#include "genflow/report/html_report.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/io/color_map.h"
#include "genflow/mesh/primitives.h"
#include "genflow/version.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// The view's data block of a page, parsed.
nlohmann::json view_data(const std::string& page) {
    const std::string open = "<script type='application/json' id='genflow-report-data'>";
    const std::size_t start = page.find(open);
    EXPECT_NE(start, std::string::npos);
    const std::size_t end = page.find("</script>", start);
    return nlohmann::json::parse(page.substr(start + open.size(), end - start - open.size()));
}

std::string decoded(const std::string& text) {
    static const std::string alphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string bytes;
    unsigned bits = 0;
    int count = 0;
    for (const char c : text) {
        if (c == '=') {
            break;
        }
        bits = (bits << 6) | static_cast<unsigned>(alphabet.find(c));
        count += 6;
        if (count >= 8) {
            count -= 8;
            bytes += static_cast<char>((bits >> count) & 0xFFU);
        }
    }
    return bytes;
}

Report sphere_report() {
    Report report;
    report.title = "a sphere";
    report.command_line = "genflow test";
    ReportMesh sphere{"sphere", make_icosphere(2), {}, true};
    sphere.attributes.scalars.emplace_back("height", sphere.mesh.V.col(2).array() + 1.0);
    report.meshes.push_back(sphere);
    report.default_coloring = "height";
    return report;
}

TEST(HtmlReport, CarriesTheMeshesExactlyAsFloatsAndIndices) {
    const Report report = sphere_report();
    const nlohmann::json data = view_data(html_report(report));
    ASSERT_EQ(data["meshes"].size(), 1U);
    const nlohmann::json& mesh = data["meshes"][0];
    EXPECT_EQ(mesh["name"], "sphere");
    const TriangleMesh& sphere = report.meshes[0].mesh;
    const std::string positions = decoded(mesh["positions"].get<std::string>());
    ASSERT_EQ(positions.size(), 4 * static_cast<std::size_t>(sphere.V.size()));
    for (Eigen::Index i = 0; i < sphere.V.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            float value = 0;
            std::memcpy(&value, positions.data() + 4 * (3 * i + c), 4);  // little-endian host
            EXPECT_EQ(value, static_cast<float>(sphere.V(i, c)));
        }
    }
    const std::string indices = decoded(mesh["indices"].get<std::string>());
    ASSERT_EQ(indices.size(), 4 * static_cast<std::size_t>(sphere.F.size()));
    for (Eigen::Index f = 0; f < sphere.F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            std::uint32_t index = 0;
            std::memcpy(&index, indices.data() + 4 * (3 * f + c), 4);
            EXPECT_EQ(index, static_cast<std::uint32_t>(sphere.F(f, c)));
        }
    }
}

// A colouring runs from 0 to its scalar's largest value, or to the top the report gives it; the
// colours are viridis_colors() of the values on that scale.
TEST(HtmlReport, ColoursEachValueOnItsScale) {
    Report report = sphere_report();
    const Eigen::VectorXd& height = report.meshes[0].attributes.scalars[0].second;
    nlohmann::json data = view_data(html_report(report));
    ASSERT_EQ(data["colorings"].size(), 1U);
    EXPECT_EQ(data["colorings"][0]["name"], "height");
    EXPECT_DOUBLE_EQ(data["colorings"][0]["top"].get<double>(), height.maxCoeff());
    EXPECT_EQ(data["default_coloring"], "height");

    report.color_scales = {{"height", 4.0}};
    data = view_data(html_report(report));
    EXPECT_DOUBLE_EQ(data["colorings"][0]["top"].get<double>(), 4.0);
    const VertexColors expected = viridis_colors(height, 0, 4.0);
    const std::string colors = decoded(data["meshes"][0]["colorings"]["height"].get<std::string>());
    ASSERT_EQ(colors.size(), static_cast<std::size_t>(expected.size()));
    EXPECT_EQ(std::memcmp(colors.data(), expected.data(), colors.size()), 0);
}

TEST(HtmlReport, OffersTheMeshesOwnColours) {
    Report report = sphere_report();
    report.meshes[0].attributes.colors =
        VertexColors::Constant(report.meshes[0].mesh.V.rows(), 3, 7);
    const nlohmann::json data = view_data(html_report(report));
    ASSERT_EQ(data["colorings"].size(), 2U);
    EXPECT_EQ(data["colorings"][0]["name"], "own colours");
    EXPECT_FALSE(data["colorings"][0].contains("top"));  // no scale to show
    EXPECT_EQ(decoded(data["meshes"][0]["colorings"]["own colours"].get<std::string>()),
              std::string(3 * static_cast<std::size_t>(report.meshes[0].mesh.V.rows()), '\7'));
}

// Text from files and command lines is escaped: it can neither add markup nor end the data
// block's <script> element.
TEST(HtmlReport, EscapesTextEverywhere) {
    Report report = sphere_report();
    report.title = "<b>bold</b> & \"quoted\"";
    report.command_line = "genflow match '</script><script>alert(1)</script>'";
    report.meshes[0].name = "</script><img src=x onerror=alert(2)>";
    report.tables.push_back({"<i>table</i>", {"<th>"}, {{"<td>"}}});
    report.plots.push_back({"<plot>", "<x>", "<y>", {{"<series>", 0, {1, 2}}}, true});
    report.details = "</pre><script>";
    const std::string page = html_report(report);
    EXPECT_EQ(page.find("<b>"), std::string::npos);
    EXPECT_NE(page.find("&lt;b&gt;bold&lt;/b&gt; &amp; &quot;quoted&quot;"), std::string::npos);
    EXPECT_EQ(page.find("<img"), std::string::npos);
    EXPECT_EQ(page.find("<i>"), std::string::npos);
    EXPECT_EQ(page.find("<plot>"), std::string::npos);
    EXPECT_EQ(page.find("<series>"), std::string::npos);
    // Every <script> the page opens is one of its own four, and each is closed once.
    std::size_t opened = 0;
    std::size_t closed = 0;
    for (std::size_t at = page.find("<script"); at != std::string::npos;
         at = page.find("<script", at + 1)) {
        ++opened;
    }
    for (std::size_t at = page.find("</script"); at != std::string::npos;
         at = page.find("</script", at + 1)) {
        ++closed;
    }
    EXPECT_EQ(opened, 4U);
    EXPECT_EQ(closed, 4U);
    EXPECT_EQ(view_data(page)["meshes"][0]["name"], report.meshes[0].name);  // read back intact
}

TEST(HtmlReport, NamesTheVersionAndInlinesEverything) {
    const std::string page = html_report(sphere_report());
    EXPECT_NE(page.find("genflow " + std::string(kVersion)), std::string::npos);
    EXPECT_NE(page.find("OrbitControls"), std::string::npos);
    EXPECT_NE(page.find("WebGLRenderer"), std::string::npos);
    // Nothing is fetched: no element loads a file or an address.
    EXPECT_EQ(page.find("<script src"), std::string::npos);
    EXPECT_EQ(page.find("<link"), std::string::npos);
    EXPECT_EQ(page.find("<img"), std::string::npos);
}

TEST(HtmlReport, WithoutMeshesIsAPageOfTablesWithoutScripts) {
    Report report;
    report.title = "numbers";
    report.tables.push_back({"t", {"a", "b"}, {{"1", "x"}}});
    const std::string page = html_report(report);
    EXPECT_EQ(page.find("<script"), std::string::npos);
    EXPECT_NE(page.find("<td class='number'>1</td><td>x</td>"), std::string::npos);
}

TEST(HtmlReport, RefusesMeshesItCannotShow) {
    Report report = sphere_report();
    report.meshes[0].mesh.F(0, 0) = static_cast<int>(report.meshes[0].mesh.V.rows());
    EXPECT_THROW((void)html_report(report), InvalidInput);
    report = sphere_report();
    report.meshes[0].mesh.V(3, 1) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW((void)html_report(report), InvalidInput);
    report = sphere_report();
    report.meshes[0].attributes.scalars[0].second.resize(3);
    EXPECT_THROW((void)html_report(report), InvalidInput);
    report = sphere_report();
    report.meshes[0].mesh.F.resize(0, 3);
    EXPECT_THROW((void)html_report(report), InvalidInput);
}

TEST(HtmlReport, IsWrittenWhole) {
    const test::TemporaryDirectory directory;
    const Report report = sphere_report();
    write_html_report(directory / "report.html", report);
    std::ifstream file(directory / "report.html", std::ios::binary);
    const std::string written((std::istreambuf_iterator<char>(file)), {});
    EXPECT_EQ(written, html_report(report));
}

TEST(Version, IsTheProjectsVersion) {
    EXPECT_EQ(kVersion, GENFLOW_PROJECT_VERSION);
}

}  // namespace
}  // namespace genflow
