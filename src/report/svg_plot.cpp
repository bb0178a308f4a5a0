// SPDX-License-Identifier: MIT
#include "report/svg_plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "report/html_escape.h"

namespace genflow::detail {

namespace {

// The plot's size in SVG units and the room left around its frame for labels.
constexpr double kWidth = 640;
constexpr double kHeight = 300;
constexpr double kLeft = 72;
constexpr double kRight = 16;
constexpr double kTop = 12;
constexpr double kBottom = 44;

// Okabe and Ito's palette: eight colours that colour-blind readers tell apart.
constexpr std::array<const char*, 8> kSeriesColors = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                      "#E69F00", "#56B4E9", "#000000", "#F0E442"};

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

std::string coordinate(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", value);
    return text;
}

// One axis: the data range as drawn (log10 of it on a logarithmic axis) and its ticks.
struct Axis {
    double low = 0;
    double high = 1;
    bool logarithmic = false;

    [[nodiscard]] double drawn(double value) const {
        return logarithmic ? std::log10(value) : value;
    }
    // Where `value` lies between low (0) and high (1).
    [[nodiscard]] double fraction(double value) const {
        return (drawn(value) - low) / (high - low);
    }
};

Axis axis_over(const std::vector<double>& values, bool logarithmic) {
    Axis axis;
    axis.logarithmic = logarithmic;
    axis.low = std::numeric_limits<double>::infinity();
    axis.high = -axis.low;
    for (const double value : values) {
        axis.low = std::min(axis.low, axis.drawn(value));
        axis.high = std::max(axis.high, axis.drawn(value));
    }
    if (!(axis.high > axis.low)) {  // one value (or none): a unit around it
        const double middle = std::isfinite(axis.low) ? axis.low : 0;
        axis.low = middle - 0.5;
        axis.high = middle + 0.5;
    }
    return axis;
}

// Round ticks over [low, high]: steps of 1, 2 or 5 times a power of ten, about five of them.
std::vector<double> linear_ticks(double low, double high) {
    const double rough = (high - low) / 5;
    const double power = std::pow(10.0, std::floor(std::log10(rough)));
    double step = 10 * power;
    for (const double mantissa : {1.0, 2.0, 5.0}) {
        if (mantissa * power >= rough) {
            step = mantissa * power;
            break;
        }
    }
    std::vector<double> values;
    for (double value = std::ceil(low / step) * step; value <= high + 1e-9 * step; value += step) {
        values.push_back(std::abs(value) < 1e-12 * step ? 0 : value);
    }
    return values;
}

// The ticks of a logarithmic axis: its decades; 1, 2 and 5 times them when fewer than two
// decades fall in the range; round linear steps when even those give fewer than two ticks.
std::vector<double> logarithmic_ticks(const Axis& axis) {
    for (const std::vector<double>& mantissas : {std::vector<double>{1}, {1, 2, 5}}) {
        std::vector<double> values;
        for (double decade = std::floor(axis.low); decade <= std::ceil(axis.high); ++decade) {
            for (const double mantissa : mantissas) {
                const double exponent = std::log10(mantissa) + decade;
                if (exponent >= axis.low - 1e-9 && exponent <= axis.high + 1e-9) {
                    values.push_back(mantissa * std::pow(10.0, decade));
                }
            }
        }
        if (values.size() >= 2) {
            return values;
        }
    }
    return linear_ticks(std::pow(10.0, axis.low), std::pow(10.0, axis.high));
}

std::vector<double> ticks(const Axis& axis) {
    return axis.logarithmic ? logarithmic_ticks(axis) : linear_ticks(axis.low, axis.high);
}

struct Frame {
    Axis x;
    Axis y;
    [[nodiscard]] double px(double value) const {
        return kLeft + x.fraction(value) * (kWidth - kLeft - kRight);
    }
    [[nodiscard]] double py(double value) const {
        return kHeight - kBottom - y.fraction(value) * (kHeight - kTop - kBottom);
    }
};

Frame frame_of(const ReportPlot& plot) {
    std::vector<double> xs;
    std::vector<double> ys;
    for (const ReportSeries& series : plot.series) {
        for (std::size_t i = 0; i < series.y.size(); ++i) {
            if (std::isfinite(series.y[i])) {
                xs.push_back(series.first_x + static_cast<double>(i));
                ys.push_back(series.y[i]);
            }
        }
    }
    const bool logarithmic = plot.log_y && !ys.empty() &&
                             std::all_of(ys.begin(), ys.end(), [](double y) { return y > 0; });
    return {axis_over(xs, false), axis_over(ys, logarithmic)};
}

std::string axes(const ReportPlot& plot, const Frame& frame) {
    std::string svg;
    const std::string bottom = coordinate(kHeight - kBottom);
    for (const double tick : ticks(frame.x)) {
        const std::string x = coordinate(frame.px(tick));
        svg += "<line x1='" + x + "' y1='" + bottom + "' x2='" + x + "' y2='" +
               coordinate(kHeight - kBottom + 4) + "' stroke='#888'/>";
        svg += "<text x='" + x + "' y='" + coordinate(kHeight - kBottom + 17) +
               "' text-anchor='middle'>" + number(tick) + "</text>";
    }
    for (const double tick : ticks(frame.y)) {
        const std::string y = coordinate(frame.py(tick));
        svg += "<line x1='" + coordinate(kLeft) + "' y1='" + y + "' x2='" +
               coordinate(kWidth - kRight) + "' y2='" + y + "' stroke='#eee'/>";
        svg += "<text x='" + coordinate(kLeft - 6) + "' y='" + y + "' dy='4' text-anchor='end'>" +
               number(tick) + "</text>";
    }
    svg += "<rect x='" + coordinate(kLeft) + "' y='" + coordinate(kTop) + "' width='" +
           coordinate(kWidth - kLeft - kRight) + "' height='" +
           coordinate(kHeight - kTop - kBottom) + "' fill='none' stroke='#888'/>";
    svg += "<text x='" + coordinate((kLeft + kWidth - kRight) / 2) + "' y='" +
           coordinate(kHeight - 8) + "' text-anchor='middle'>" + escape_html(plot.x_label) +
           "</text>";
    svg += "<text transform='translate(14 " + coordinate((kTop + kHeight - kBottom) / 2) +
           ") rotate(-90)' text-anchor='middle'>" + escape_html(plot.y_label) +
           (frame.y.logarithmic ? " (log scale)" : "") + "</text>";
    return svg;
}

// A series as polylines, broken where a value is not finite.
std::string lines(const ReportSeries& series, const Frame& frame, const char* color) {
    std::string svg;
    std::string points;
    const auto flush = [&] {
        if (!points.empty()) {
            svg += "<polyline fill='none' stroke='" + std::string(color) +
                   "' stroke-width='1.6' points='" + points + "'/>";
            points.clear();
        }
    };
    for (std::size_t i = 0; i < series.y.size(); ++i) {
        if (!std::isfinite(series.y[i]) || (frame.y.logarithmic && !(series.y[i] > 0))) {
            flush();
            continue;
        }
        if (!points.empty()) {
            points += ' ';
        }
        points += coordinate(frame.px(series.first_x + static_cast<double>(i)));
        points += ',';
        points += coordinate(frame.py(series.y[i]));
    }
    flush();
    return svg;
}

std::string legend(const ReportPlot& plot) {
    std::string svg;
    for (std::size_t s = 0; s < plot.series.size(); ++s) {
        const std::string y = coordinate(kTop + 14 + 16 * static_cast<double>(s));
        const std::string x = coordinate(kWidth - kRight - 150);
        svg += "<line x1='" + x + "' y1='" + y + "' x2='" + coordinate(kWidth - kRight - 130) +
               "' y2='" + y + "' stroke='" + kSeriesColors[s % kSeriesColors.size()] +
               "' stroke-width='2'/>";
        svg += "<text x='" + coordinate(kWidth - kRight - 124) + "' y='" + y + "' dy='4'>" +
               escape_html(plot.series[s].name) + "</text>";
    }
    return svg;
}

}  // namespace

std::string svg_line_plot(const ReportPlot& plot) {
    const Frame frame = frame_of(plot);
    std::string svg = "<svg class='plot' xmlns='http://www.w3.org/2000/svg' viewBox='0 0 " +
                      coordinate(kWidth) + " " + coordinate(kHeight) + "' width='" +
                      coordinate(kWidth) + "' height='" + coordinate(kHeight) + "' role='img'>";
    svg += "<title>" + escape_html(plot.title) + "</title>";
    svg += axes(plot, frame);
    for (std::size_t s = 0; s < plot.series.size(); ++s) {
        svg += lines(plot.series[s], frame, kSeriesColors[s % kSeriesColors.size()]);
    }
    svg += legend(plot);
    return svg + "</svg>";
}

}  // namespace genflow::detail
