// SPDX-License-Identifier: MIT
#include "number_checks.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <optional>
#include <string>

#include "genflow/mesh/validate.h"

namespace genflow::cli {

namespace {

// The whole of `text` as a number (nan and inf included), or nothing.
std::optional<double> number_of(const std::string& text) {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size()) {
        return std::nullopt;
    }
    return value;
}

// A bound as people write it: 1e+06, 0.5, not a double's every digit.
std::string shown(double bound) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", bound);
    return text;
}

// A validator that accepts the numbers `accepts` says yes to, else says "must be <expected>".
CLI::Validator expecting(const std::string& expected, std::function<bool(double)> accepts,
                         const std::string& type_name) {
    return CLI::Validator(
        [expected, accepts](const std::string& text) {
            const std::optional<double> value = number_of(text);
            return value && accepts(*value) ? std::string()
                                            : "must be " + expected + ", got " + text;
        },
        type_name);
}

}  // namespace

CLI::Validator positive_number() {
    return expecting(
        "a positive number", [](double x) { return std::isfinite(x) && x > 0; }, "POSITIVE");
}

CLI::Validator positive_length() {
    return expecting(
        "a positive length up to " + shown(kLargestCoordinate),
        [](double x) { return std::isfinite(x) && x > 0 && x <= kLargestCoordinate; }, "LENGTH");
}

CLI::Validator non_negative_number() {
    return expecting(
        "a number >= 0", [](double x) { return std::isfinite(x) && x >= 0; }, "NONNEGATIVE");
}

CLI::Validator number_in(double low, double high) {
    const std::string range = "[" + shown(low) + ", " + shown(high) + "]";
    return expecting(
        "a number in " + range,
        [low, high](double x) { return std::isfinite(x) && x >= low && x <= high; }, "in " + range);
}

CLI::Validator non_negative_or_infinity() {
    return expecting(
        "a number >= 0 or inf", [](double x) { return !std::isnan(x) && x >= 0; },
        "NONNEGATIVE or inf");
}

}  // namespace genflow::cli
