// SPDX-License-Identifier: MIT
// Checks of numeric options. CLI11's own (PositiveNumber, Range, …) let nan through, as nan
// compares false with every bound, and print their bounds with all their digits; these refuse
// nan and infinities and say what was expected: "--lambda: must be a positive number, got nan".
#pragma once

#include <CLI/CLI.hpp>

namespace genflow::cli {

/// A finite number > 0.
[[nodiscard]] CLI::Validator positive_number();

/// A number in (0, kLargestCoordinate]: a length, which is squared as coordinates are.
[[nodiscard]] CLI::Validator positive_length();

/// A finite number >= 0.
[[nodiscard]] CLI::Validator non_negative_number();

/// A finite number in [low, high].
[[nodiscard]] CLI::Validator number_in(double low, double high);

/// A number >= 0, or inf for "never" (a threshold).
[[nodiscard]] CLI::Validator non_negative_or_infinity();

}  // namespace genflow::cli
