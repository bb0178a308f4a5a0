// SPDX-License-Identifier: MIT
#include "genflow/io/color_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "genflow/exceptions.h"

namespace genflow {

namespace {

// Viridis (CC0) at 33 evenly spaced points, rounded to 0–255; linear interpolation between them
// stays within 2.5 levels of the full 256-entry table.
constexpr std::array<std::array<int, 3>, 33> kViridis = {{
    {68, 1, 84},    {71, 13, 96},   {72, 24, 106},  {72, 35, 116},  {71, 45, 123},  {69, 55, 129},
    {66, 64, 134},  {62, 73, 137},  {59, 82, 139},  {55, 91, 141},  {51, 99, 141},  {47, 107, 142},
    {44, 114, 142}, {41, 122, 142}, {38, 130, 142}, {35, 137, 142}, {33, 145, 140}, {31, 152, 139},
    {31, 160, 136}, {34, 167, 133}, {40, 174, 128}, {50, 182, 122}, {63, 188, 115}, {78, 195, 107},
    {94, 201, 98},  {112, 207, 87}, {132, 212, 75}, {152, 216, 62}, {173, 220, 48}, {194, 223, 35},
    {216, 226, 25}, {236, 229, 27}, {253, 231, 37},
}};

constexpr std::uint8_t kGrey = 128;

}  // namespace

VertexColors viridis_colors(const Eigen::VectorXd& values, double low, double high) {
    if (!(std::isfinite(low) && std::isfinite(high) && low < high)) {
        throw InvalidInput("viridis_colors: the scale needs finite low < high, got [" +
                           std::to_string(low) + ", " + std::to_string(high) + "]");
    }
    VertexColors colors(values.size(), 3);
    constexpr double last = kViridis.size() - 1;
    for (Eigen::Index i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i])) {
            colors.row(i).setConstant(kGrey);
            continue;
        }
        const double t = std::clamp((values[i] - low) / (high - low), 0.0, 1.0) * last;
        const auto k = static_cast<std::size_t>(std::min(std::floor(t), last - 1));
        const double w = t - static_cast<double>(k);
        for (int c = 0; c < 3; ++c) {
            const double value = (1 - w) * kViridis[k][c] + w * kViridis[k + 1][c];
            colors(i, c) = static_cast<std::uint8_t>(std::lround(value));
        }
    }
    return colors;
}

}  // namespace genflow
