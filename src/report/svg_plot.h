// SPDX-License-Identifier: MIT
// A report's line plots as inline SVG: axes with round ticks, a line per series, a legend.
#pragma once

#include <string>

#include "genflow/report/html_report.h"

namespace genflow::detail {

/// `plot` as an <svg> element. Non-finite values break their line; a logarithmic axis is used
/// when asked for and every value is positive.
[[nodiscard]] std::string svg_line_plot(const ReportPlot& plot);

}  // namespace genflow::detail
