// SPDX-License-Identifier: MIT
// Text made safe to place in HTML and SVG, between tags or in a quoted attribute.
#pragma once

#include <string>
#include <string_view>

namespace genflow::detail {

[[nodiscard]] inline std::string escape_html(std::string_view text) {
    std::string escaped;
    escaped.reserve(text.size());
    for (const char c : text) {
        switch (c) {
            case '&':
                escaped += "&amp;";
                break;
            case '<':
                escaped += "&lt;";
                break;
            case '>':
                escaped += "&gt;";
                break;
            case '"':
                escaped += "&quot;";
                break;
            case '\'':
                escaped += "&#39;";
                break;
            default:
                escaped += c;
        }
    }
    return escaped;
}

}  // namespace genflow::detail
