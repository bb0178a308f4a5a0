// SPDX-License-Identifier: MIT
#include "genflow/io/color_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "genflow/exceptions.h"

namespace genflow {
namespace {

// Relative luminance of an sRGB colour (IEC 61966-2-1 linearization, Rec. 709 weights).
double luminance(const VertexColors& colors, Eigen::Index row) {
    const auto linear = [](std::uint8_t value) {
        const double c = value / 255.0;
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    return 0.2126 * linear(colors(row, 0)) + 0.7152 * linear(colors(row, 1)) +
           0.0722 * linear(colors(row, 2));
}

// The ends are viridis' own (#440154 and #FDE725), values beyond the scale take the ends, and
// the lightness rises all the way: a larger value reads as lighter, also in grey (within the
// rounding to 0–255, which can undo a step of a few thousandths).
TEST(ColorMap, RunsFromDarkPurpleToYellowGettingLighter) {
    const Eigen::VectorXd values = Eigen::VectorXd::LinSpaced(1001, -1, 3);  // scale [0, 2]
    const VertexColors colors = viridis_colors(values, 0, 2);
    EXPECT_EQ(colors.row(0), (VertexColors::RowXpr::PlainObject() << 68, 1, 84).finished());
    EXPECT_EQ(colors.row(250), colors.row(0));  // value 0
    EXPECT_EQ(colors.row(1000), (VertexColors::RowXpr::PlainObject() << 253, 231, 37).finished());
    EXPECT_EQ(colors.row(750), colors.row(1000));    // value 2
    for (Eigen::Index i = 260; i <= 750; i += 10) {  // fiftieths of the scale
        EXPECT_GT(luminance(colors, i), luminance(colors, i - 10)) << values[i];
    }
    EXPECT_GT(luminance(colors, 750), 10 * luminance(colors, 250));
}

TEST(ColorMap, ColoursAMissingValueGreyAndRefusesAnEmptyScale) {
    const Eigen::VectorXd values =
        (Eigen::VectorXd(2) << std::numeric_limits<double>::quiet_NaN(), 0.5).finished();
    const VertexColors colors = viridis_colors(values, 0, 1);
    EXPECT_EQ(colors(0, 0), 128);
    EXPECT_EQ(colors(0, 1), 128);
    EXPECT_EQ(colors(0, 2), 128);
    EXPECT_THROW((void)viridis_colors(values, 1, 1), InvalidInput);
    EXPECT_THROW((void)viridis_colors(values, 0, std::numeric_limits<double>::infinity()),
                 InvalidInput);
}

}  // namespace
}  // namespace genflow
