// SPDX-License-Identifier: MIT
#pragma once

#include <string_view>

namespace genflow {

/// genflow's version, as the project() call of CMakeLists.txt gives it (a test holds them
/// equal): reports and `genflow --version` print it.
inline constexpr std::string_view kVersion = "0.1.0";

}  // namespace genflow
