// SPDX-License-Identifier: MIT
#include "report/report_assets.h"

namespace genflow::detail {

namespace {

constexpr unsigned char kThreeJs[] = {
#include "three.min.js.inc"
};
constexpr unsigned char kOrbitControlsJs[] = {
#include "OrbitControls.js.inc"
};
constexpr unsigned char kViewerJs[] = {
#include "viewer.js.inc"
};
constexpr unsigned char kReportCss[] = {
#include "report.css.inc"
};

template <std::size_t N>
std::string_view text_of(const unsigned char (&bytes)[N]) {
    return {reinterpret_cast<const char*>(bytes), N};
}

}  // namespace

std::string_view three_js() {
    return text_of(kThreeJs);
}
std::string_view orbit_controls_js() {
    return text_of(kOrbitControlsJs);
}
std::string_view viewer_js() {
    return text_of(kViewerJs);
}
std::string_view report_css() {
    return text_of(kReportCss);
}

}  // namespace genflow::detail
