// SPDX-License-Identifier: MIT
// The matcher's stages report how long they took (MatchResult, MatchLevel).
#pragma once

#include <chrono>

namespace genflow::detail {

/// Seconds from `t` to now, on the steady clock.
[[nodiscard]] inline double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace genflow::detail
