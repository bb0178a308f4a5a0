// SPDX-License-Identifier: MIT
#include "report/svg_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace genflow {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
        ++n;
    }
    return n;
}

TEST(SvgPlot, DrawsALinePerSeriesAndNamesThemInTheLegend) {
    const ReportPlot plot{
        "energy", "step", "E", {{"first", 0, {3, 2, 1}}, {"second", 3, {1, 0.5}}}, true};
    const std::string svg = detail::svg_line_plot(plot);
    EXPECT_EQ(svg.rfind("<svg", 0), 0U);
    EXPECT_EQ(count(svg, "<polyline"), 2U);
    EXPECT_NE(svg.find(">first<"), std::string::npos);
    EXPECT_NE(svg.find(">second<"), std::string::npos);
    EXPECT_NE(svg.find("(log scale)"), std::string::npos);
    // Decades and 1-2-5 ticks within them: 0.5 to 3 spans less than two decades.
    EXPECT_NE(svg.find(">0.5<"), std::string::npos);
    EXPECT_NE(svg.find(">1<"), std::string::npos);
    EXPECT_NE(svg.find(">2<"), std::string::npos);
}

// Values within one 1-2-5 step of a decade still get two ticks or more, round ones.
TEST(SvgPlot, TicksANarrowLogarithmicRange) {
    const std::string svg =
        detail::svg_line_plot({"", "x", "y", {{"s", 0, {0.0476, 0.04, 0.035}}}, true});
    EXPECT_NE(svg.find("(log scale)"), std::string::npos);
    EXPECT_NE(svg.find(">0.04<"), std::string::npos);
    EXPECT_NE(svg.find(">0.045<"), std::string::npos);
}

TEST(SvgPlot, BreaksALineAtAValueThatIsNotFinite) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const ReportPlot plot{"", "x", "y", {{"broken", 0, {1, 2, nan, 4, 5}}}, true};
    const std::string svg = detail::svg_line_plot(plot);
    EXPECT_EQ(count(svg, "<polyline"), 2U);
    EXPECT_EQ(svg.find("nan"), std::string::npos);
}

// A logarithmic axis only for positive values: with a zero or a negative value the axis is
// linear, with round ticks.
TEST(SvgPlot, UsesALinearAxisForValuesThatAreNotAllPositive) {
    const ReportPlot plot{"", "x", "y", {{"s", 0, {-1, 0, 1.5}}}, true};
    const std::string svg = detail::svg_line_plot(plot);
    EXPECT_EQ(svg.find("(log scale)"), std::string::npos);
    EXPECT_NE(svg.find(">-1<"), std::string::npos);
    EXPECT_NE(svg.find(">0<"), std::string::npos);
    EXPECT_NE(svg.find(">1.5<"), std::string::npos);
    EXPECT_EQ(count(svg, "<polyline"), 1U);
}

TEST(SvgPlot, DrawsAnEmptyFrameForNoValues) {
    const std::string svg = detail::svg_line_plot({"", "x", "y", {}, true});
    EXPECT_EQ(count(svg, "<polyline"), 0U);
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    EXPECT_EQ(svg.find("inf"), std::string::npos);
}

}  // namespace
}  // namespace genflow
