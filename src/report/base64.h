// SPDX-License-Identifier: MIT
// Base64 (RFC 4648, with padding): how a report carries its meshes' arrays as text.
#pragma once

#include <string>
#include <string_view>

namespace genflow::detail {

[[nodiscard]] std::string base64(std::string_view bytes);

}  // namespace genflow::detail
