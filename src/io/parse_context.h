// SPDX-License-Identifier: MIT
// Private helpers shared by the mesh readers: error reporting, polygon collection and
// fan triangulation, and a bounds-checked cursor over text.
#pragma once

#include <charconv>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/mesh.h"

namespace genflow::detail {

/// Where a reader reports to: the name used in messages and the optional warning sink.
struct ParseContext {
    std::string_view source;
    std::vector<std::string>* warnings = nullptr;

    [[noreturn]] void fail(const std::string& problem) const {
        throw IoError(std::string(source) + ": " + problem);
    }
    void warn(const std::string& message) const {
        if (warnings != nullptr) {
            warnings->push_back(std::string(source) + ": " + message);
        }
    }
};

/// Collects vertices and polygons as a reader finds them and turns them into a TriangleMesh,
/// splitting polygons into fans around their first corner.
class MeshBuilder {
public:
    explicit MeshBuilder(const ParseContext& context) : context_(context) {}

    /// Reserves room for `count` items, but never more than `bytes_left / min_bytes_per_item`:
    /// a corrupt header must not make us allocate memory the file cannot fill.
    static std::size_t safe_reserve(std::uint64_t count, std::size_t bytes_left,
                                    std::size_t min_bytes_per_item) {
        const std::uint64_t affordable =
            bytes_left / (min_bytes_per_item > 0 ? min_bytes_per_item : 1);
        return static_cast<std::size_t>(count < affordable ? count : affordable);
    }

    void reserve(std::size_t vertices, std::size_t faces) {
        positions_.reserve(3 * vertices);
        triangles_.reserve(3 * faces);
    }
    void add_vertex(double x, double y, double z) {
        positions_.push_back(x);
        positions_.push_back(y);
        positions_.push_back(z);
    }
    [[nodiscard]] std::size_t num_vertices() const { return positions_.size() / 3; }

    /// Adds a polygon given by its corner indices (0-based, not yet range-checked).
    void add_polygon(const std::vector<std::int64_t>& corners);

    /// Converts a vertex index read from a file into an int, failing on values no mesh can
    /// address. Range checks against #V are `validate()`'s job.
    [[nodiscard]] std::int64_t checked_index(double value) const;

    [[nodiscard]] TriangleMesh finish();

private:
    const ParseContext& context_;
    std::vector<double> positions_;
    std::vector<int> triangles_;
    std::size_t split_polygons_ = 0;
    std::size_t dropped_polygons_ = 0;
};

/// A cursor over text that reads whitespace-separated tokens, numbers and lines without ever
/// reading past the end.
/// The UTF-8 encoding of U+FEFF, which some editors put at the start of a text file.
inline constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

class TextScanner {
public:
    /// A UTF-8 byte order mark at the start (some Windows editors write one) is skipped: it is
    /// not content, and read as such it spoils the first line.
    explicit TextScanner(std::string_view text) : text_(text) {
        if (text_.starts_with(kByteOrderMark)) {
            pos_ = kByteOrderMark.size();
        }
    }

    [[nodiscard]] bool at_end() const { return pos_ >= text_.size(); }
    [[nodiscard]] std::size_t bytes_left() const { return text_.size() - pos_; }
    [[nodiscard]] std::size_t position() const { return pos_; }
    [[nodiscard]] std::size_t line_number() const;

    /// The next line without its terminator ("\n", "\r\n" or "\r"); empty at the end.
    std::string_view next_line();

    /// The next whitespace-separated token; empty at the end.
    std::string_view next_token();

private:
    std::string_view text_;
    std::size_t pos_ = 0;
};

/// Splits a line into whitespace-separated tokens, reusing the storage of `tokens` (the readers
/// call this once per line, so it must not allocate every time).
void split_tokens(std::string_view line, std::vector<std::string_view>& tokens);

/// Parses a complete token as a double ("1", "-2.5e3", "nan", "inf"; a leading '+' is allowed).
[[nodiscard]] bool parse_double(std::string_view token, double& value);

/// Parses a complete token as a signed 64-bit integer (a leading '+' is allowed).
[[nodiscard]] bool parse_integer(std::string_view token, std::int64_t& value);

/// One line of a line-based text file that has content: its whitespace-separated tokens, without
/// its comment (from a '#' to the end of the line).
struct DataLine {
    std::vector<std::string_view> tokens;
    std::size_t number = 0;  ///< 1-based, as editors count
    const std::filesystem::path* path = nullptr;

    /// Throws IoError "<path>: line <number>: <problem>".
    [[noreturn]] void fail(const std::string& problem) const;
};

/// Reads the text file at `path` and calls `visit` on each of its lines that has content;
/// blank and comment-only lines are skipped but counted.
void for_each_data_line(const std::filesystem::path& path,
                        const std::function<void(const DataLine&)>& visit);

/// Case-insensitive ASCII comparison.
[[nodiscard]] bool iequals(std::string_view a, std::string_view b);

/// A colour channel as a byte: `value` in 0–1 where `unit`, else in 0–255; rounded, and clamped
/// to the byte's range.
[[nodiscard]] std::uint8_t color_byte(double value, bool unit);

}  // namespace genflow::detail
