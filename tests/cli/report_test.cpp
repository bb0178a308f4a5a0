// SPDX-License-Identifier: MIT
// --report of match, smooth and distance, and the page as a browser shows it: headless
// Chromium (Debian's chromium) renders a report; the page must say that it drew and met no
// error, and its screenshot must hold the meshes' pixels.
#include <gtest/gtest.h>
#include <png.h>
#include <sys/wait.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_runner.h"
#include "genflow/io/write_mesh.h"
#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

using test::quoted;
using test::read_text;
using test::run_genflow;

// The view's data block of a report page, parsed.
nlohmann::json view_data(const std::string& page) {
    const std::string open = "<script type='application/json' id='genflow-report-data'>";
    const std::size_t start = page.find(open);
    if (start == std::string::npos) {
        return nullptr;
    }
    const std::size_t end = page.find("</script>", start);
    return nlohmann::json::parse(page.substr(start + open.size(), end - start - open.size()));
}

// A limb and a finer limb turned and moved: a match with something to show.
void write_pair(const test::TemporaryDirectory& directory) {
    TriangleMesh target = make_limb(4, 5);
    target.V =
        (target.V * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix()).rowwise() +
        Eigen::RowVector3d(0.5, 0, 0);
    write_mesh(directory / "template.ply", make_limb(3));
    write_mesh(directory / "target.ply", target);
}

// Headless Chromium on a page: its exit code and what it printed on stdout.
struct BrowserRun {
    int exit_code = -1;
    std::string out;
};

BrowserRun run_chromium(const std::filesystem::path& page, const std::string& arguments,
                        const test::TemporaryDirectory& scratch) {
    // Its own profile per run (parallel tests do not share one); no sandbox, which needs
    // privileges a test run may not have; WebGL drawn by SwiftShader on the processor.
    const std::string command =
        "timeout 120 '" + std::string(GENFLOW_CHROMIUM_PATH) +
        "' --headless --no-sandbox --enable-unsafe-swiftshader --hide-scrollbars "
        "--window-size=1000,900 --user-data-dir=" +
        quoted(scratch / "profile") + " " + arguments + " 'file://" + page.string() + "' >" +
        quoted(scratch / "chromium.out") + " 2>" + quoted(scratch / "chromium.err");
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(scratch / "chromium.out")};
}

// An RGB image read by libpng.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<unsigned char> rgb;
};

Image read_png(const std::filesystem::path& path) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    Image image;
    if (png_image_begin_read_from_file(&png, path.c_str()) == 0) {
        return image;
    }
    png.format = PNG_FORMAT_RGB;
    image.rgb.resize(PNG_IMAGE_SIZE(png));
    if (png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr) == 0) {
        return {};
    }
    image.width = static_cast<int>(png.width);
    image.height = static_cast<int>(png.height);
    return image;
}

// The <body> tag of the page as the browser left it.
std::string body_tag(const std::string& dom) {
    const std::size_t start = dom.find("<body");
    return start == std::string::npos ? "" : dom.substr(start, dom.find('>', start) - start + 1);
}

TEST(ReportCli, MatchReportIsDrawnInABrowser) {
    ASSERT_TRUE(std::filesystem::exists(GENFLOW_CHROMIUM_PATH))
        << "the browser test needs Debian's chromium (scripts/install-deps.sh installs it)";
    const test::TemporaryDirectory directory;
    write_pair(directory);
    const auto matched = run_genflow(
        "match " + quoted(directory / "template.ply") + " " + quoted(directory / "target.ply") +
        " -o " + quoted(directory / "out.ply") +
        " --prior rigid --iterations 40 --quiet --report " + quoted(directory / "shown.html"));
    ASSERT_EQ(matched.exit_code, 0) << matched.err;
    // The same page with every mesh hidden: what differs between the two is the meshes.
    std::string page = read_text(directory / "shown.html");
    for (std::size_t at = page.find("\"shown\":true"); at != std::string::npos;
         at = page.find("\"shown\":true", at)) {
        page.replace(at, 12, "\"shown\":false");
    }
    {
        std::ofstream hidden(directory / "hidden.html", std::ios::binary);
        hidden << page;
    }
    for (const char* name : {"shown", "hidden"}) {
        const BrowserRun dom =
            run_chromium(directory / (std::string(name) + ".html"), "--dump-dom", directory);
        ASSERT_EQ(dom.exit_code, 0) << read_text(directory / "chromium.err");
        EXPECT_NE(body_tag(dom.out).find("data-status=\"drawn\""), std::string::npos)
            << name << ": " << body_tag(dom.out);
        EXPECT_EQ(body_tag(dom.out).find("data-error"), std::string::npos)
            << name << ": " << body_tag(dom.out);
        const BrowserRun shot = run_chromium(
            directory / (std::string(name) + ".html"),
            "--screenshot=" + quoted(directory / (std::string(name) + ".png")), directory);
        ASSERT_EQ(shot.exit_code, 0) << read_text(directory / "chromium.err");
    }
    const Image shown = read_png(directory / "shown.png");
    const Image hidden = read_png(directory / "hidden.png");
    ASSERT_GT(shown.width, 0);
    ASSERT_EQ(shown.width, hidden.width);
    ASSERT_EQ(shown.height, hidden.height);
    std::size_t mesh_pixels = 0;
    std::size_t colored_pixels = 0;
    for (std::size_t p = 0; p + 2 < shown.rgb.size(); p += 3) {
        int difference = 0;
        for (int c = 0; c < 3; ++c) {
            difference = std::max(difference, std::abs(shown.rgb[p + c] - hidden.rgb[p + c]));
        }
        if (difference > 8) {
            ++mesh_pixels;
            const auto [low, high] =
                std::minmax({shown.rgb[p], shown.rgb[p + 1], shown.rgb[p + 2]});
            colored_pixels += high - low > 40 ? 1 : 0;  // viridis, not the plain grey
        }
    }
    const auto pixels =
        static_cast<std::size_t>(shown.width) * static_cast<std::size_t>(shown.height);
    EXPECT_GT(mesh_pixels, pixels / 50) << "the meshes cover too little of the view";
    // The result is coloured by its distance to the target, the template plain grey.
    EXPECT_GT(colored_pixels, mesh_pixels / 10);
}

TEST(ReportCli, SmoothAndDistanceWriteTheirReports) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "bumpy.ply", add_noise(make_icosphere(3), 0.02, 7));
    write_mesh(directory / "sphere.ply", make_icosphere(3));
    const auto smoothed = run_genflow("smooth " + quoted(directory / "bumpy.ply") + " " +
                                      quoted(directory / "smooth.ply") + " --steps 5 --report " +
                                      quoted(directory / "smooth.html"));
    ASSERT_EQ(smoothed.exit_code, 0) << smoothed.err;
    EXPECT_NE(smoothed.out.find("smooth.html"), std::string::npos);
    const nlohmann::json smooth = view_data(read_text(directory / "smooth.html"));
    ASSERT_EQ(smooth["meshes"].size(), 2U);
    EXPECT_EQ(smooth["meshes"][1]["name"], "smoothed");
    EXPECT_EQ(smooth["default_coloring"], "");  // the shading shows the change
    EXPECT_EQ(smooth["colorings"][0]["name"], "displacement");
    EXPECT_NE(read_text(directory / "smooth.html").find("<polyline"), std::string::npos);

    const auto distance = run_genflow("distance " + quoted(directory / "bumpy.ply") + " " +
                                      quoted(directory / "sphere.ply") + " --json --report " +
                                      quoted(directory / "distance.html"));
    ASSERT_EQ(distance.exit_code, 0) << distance.err;
    const nlohmann::json summary = nlohmann::json::parse(distance.out);
    const nlohmann::json data = view_data(read_text(directory / "distance.html"));
    ASSERT_EQ(data["meshes"].size(), 2U);
    ASSERT_EQ(data["colorings"].size(), 1U);
    // Both meshes on one scale, up to the symmetric Hausdorff distance.
    EXPECT_DOUBLE_EQ(data["colorings"][0]["top"].get<double>(), summary["hausdorff"].get<double>());
    EXPECT_EQ(summary["report"], (directory / "distance.html").string());
}

}  // namespace
}  // namespace genflow
