// SPDX-License-Identifier: MIT
// The scripts and style sheet a report carries inline, built into the library from their files
// (cmake/EmbedBytes.cmake): three.js and its orbit controls from Debian's libjs-three, and the
// project's own view script and style.
#pragma once

#include <string_view>

namespace genflow::detail {

[[nodiscard]] std::string_view three_js();
[[nodiscard]] std::string_view orbit_controls_js();
[[nodiscard]] std::string_view viewer_js();
[[nodiscard]] std::string_view report_css();

}  // namespace genflow::detail
