// SPDX-License-Identifier: MIT
#include "io/parse_context.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "genflow/io/read_file.h"
#include "io/corner_data.h"

namespace genflow::detail {

void MeshBuilder::add_polygon(const std::vector<std::int64_t>& corners) {
    if (corners.size() < 3) {
        ++dropped_polygons_;
        return;
    }
    if (corners.size() > 3) {
        ++split_polygons_;
    }
    append_fan(corners, triangles_);
}

std::int64_t MeshBuilder::checked_index(double value) const {
    // Indices beyond int range cannot address any mesh we can hold; keep in-range negative
    // values so that validate() can name them.
    constexpr double kMax = std::numeric_limits<int>::max();
    if (!std::isfinite(value) || std::abs(value) > kMax || value != std::floor(value)) {
        context_.fail("vertex index " + std::to_string(value) + " is not a valid integer index");
    }
    return static_cast<std::int64_t>(value);
}

TriangleMesh MeshBuilder::finish() {
    if (split_polygons_ > 0) {
        context_.warn(std::to_string(split_polygons_) +
                      " polygon(s) with more than 3 corners were split into triangle fans");
    }
    if (dropped_polygons_ > 0) {
        context_.warn(std::to_string(dropped_polygons_) +
                      " face(s) with fewer than 3 corners were dropped");
    }
    TriangleMesh mesh;
    const auto n = static_cast<Eigen::Index>(num_vertices());
    const auto m = static_cast<Eigen::Index>(triangles_.size() / 3);
    mesh.V = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
        positions_.data(), n, 3);
    mesh.F = Eigen::Map<const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(
        triangles_.data(), m, 3);
    return mesh;
}

std::size_t TextScanner::line_number() const {
    return 1 + static_cast<std::size_t>(std::count(
                   text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(pos_), '\n'));
}

std::string_view TextScanner::next_line() {
    if (at_end()) {
        return {};
    }
    const std::size_t begin = pos_;
    std::size_t end = begin;
    while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') {
        ++end;
    }
    pos_ = end;
    if (pos_ < text_.size() && text_[pos_] == '\r') {
        ++pos_;
    }
    if (pos_ < text_.size() && text_[pos_] == '\n') {
        ++pos_;
    }
    return text_.substr(begin, end - begin);
}

namespace {
bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}
}  // namespace

std::string_view TextScanner::next_token() {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
        ++pos_;
    }
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) {
        ++pos_;
    }
    return text_.substr(begin, pos_ - begin);
}

void split_tokens(std::string_view line, std::vector<std::string_view>& tokens) {
    tokens.clear();
    TextScanner scanner(line);
    for (auto token = scanner.next_token(); !token.empty(); token = scanner.next_token()) {
        tokens.push_back(token);
    }
}

namespace {

// A complete token as a number of type T; a leading '+' is allowed (from_chars refuses it).
template <typename T>
bool parse_number(std::string_view token, T& value) {
    if (!token.empty() && token.front() == '+') {
        token.remove_prefix(1);
    }
    if (token.empty()) {
        return false;
    }
    const auto* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, value);
    return ec == std::errc() && ptr == end;
}

}  // namespace

bool parse_double(std::string_view token, double& value) {
    return parse_number(token, value);
}

bool parse_integer(std::string_view token, std::int64_t& value) {
    return parse_number(token, value);
}

bool iequals(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

void DataLine::fail(const std::string& problem) const {
    throw IoError(path->string() + ": line " + std::to_string(number) + ": " + problem);
}

void for_each_data_line(const std::filesystem::path& path,
                        const std::function<void(const DataLine&)>& visit) {
    const std::string text = read_file(path);
    TextScanner scanner(text);
    DataLine line;
    line.path = &path;
    for (line.number = 1; !scanner.at_end(); ++line.number) {
        const std::string_view content = scanner.next_line();
        split_tokens(content.substr(0, content.find('#')), line.tokens);
        if (!line.tokens.empty()) {
            visit(line);
        }
    }
}

std::uint8_t color_byte(double value, bool unit) {
    const double scaled = unit ? 255 * value : value;
    return static_cast<std::uint8_t>(std::lround(std::clamp(scaled, 0.0, 255.0)));
}

}  // namespace genflow::detail
