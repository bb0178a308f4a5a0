// SPDX-License-Identifier: MIT
// Object File Format (Geomview): "OFF", counts "nV nF nE", nV vertex lines, nF face lines
// "k i1 ... ik [colour]". Prefix variants (C, N, ST, CN, ...) only add per-vertex columns after
// x y z, which we skip. Comments start with '#'.
#include <limits>
#include <string>

#include "io/readers.h"

namespace genflow::detail {

namespace {

// Yields the tokens of the next line that holds any, with comments stripped.
class OffLines {
public:
    explicit OffLines(std::string_view bytes) : scanner_(bytes) {}

    bool next(std::vector<std::string_view>& tokens) {
        while (!scanner_.at_end()) {
            const auto line = scanner_.next_line();
            ++line_number_;
            split_tokens(line.substr(0, line.find('#')), tokens);
            if (!tokens.empty()) {
                return true;
            }
        }
        return false;
    }
    [[nodiscard]] std::size_t line_number() const { return line_number_; }
    [[nodiscard]] std::size_t bytes_left() const { return scanner_.bytes_left(); }

private:
    TextScanner scanner_;
    std::size_t line_number_ = 0;
};

bool is_off_keyword(std::string_view word) {
    if (word.size() < 3 || word.substr(word.size() - 3) != "OFF") {
        return false;
    }
    // Accept ST, C, N, 4 and n prefixes only in the plain 3D forms.
    for (char c : word.substr(0, word.size() - 3)) {
        if (c != 'S' && c != 'T' && c != 'C' && c != 'N') {
            return false;
        }
    }
    return true;
}

}  // namespace

TriangleMesh parse_off(std::string_view bytes, const ParseContext& context) {
    OffLines lines(bytes);
    std::vector<std::string_view> tokens;
    const auto at_line = [&] { return "line " + std::to_string(lines.line_number()) + ": "; };

    if (!lines.next(tokens)) {
        context.fail("empty file");
    }
    if (!is_off_keyword(tokens[0])) {
        context.fail("not an OFF file (first word is '" + std::string(tokens[0].substr(0, 32)) +
                     "', expected OFF)");
    }
    if (tokens.size() > 1 && tokens[1] == "BINARY") {
        context.fail("binary OFF is not supported");
    }
    std::vector<std::string_view> counts(tokens.begin() + 1, tokens.end());
    if (counts.empty()) {
        if (!lines.next(counts)) {
            context.fail("missing vertex and face counts");
        }
    }
    std::int64_t num_vertices = 0;
    std::int64_t num_faces = 0;
    if (counts.size() < 2 || !parse_integer(counts[0], num_vertices) ||
        !parse_integer(counts[1], num_faces) || num_vertices < 0 || num_faces < 0) {
        context.fail(at_line() + "bad counts, expected 'num_vertices num_faces num_edges'");
    }

    MeshBuilder builder(context);
    // Every vertex line needs at least 6 bytes ("0 0 0\n"), every face line at least 8.
    builder.reserve(
        MeshBuilder::safe_reserve(static_cast<std::uint64_t>(num_vertices), lines.bytes_left(), 6),
        MeshBuilder::safe_reserve(static_cast<std::uint64_t>(num_faces), lines.bytes_left(), 8));
    for (std::int64_t i = 0; i < num_vertices; ++i) {
        double xyz[3];
        if (!lines.next(tokens)) {
            context.fail("file ends after " + std::to_string(i) + " of " +
                         std::to_string(num_vertices) + " vertices");
        }
        if (tokens.size() < 3 || !parse_double(tokens[0], xyz[0]) ||
            !parse_double(tokens[1], xyz[1]) || !parse_double(tokens[2], xyz[2])) {
            context.fail(at_line() + "malformed vertex");
        }
        builder.add_vertex(xyz[0], xyz[1], xyz[2]);
    }
    std::vector<std::int64_t> corners;
    for (std::int64_t f = 0; f < num_faces; ++f) {
        if (!lines.next(tokens)) {
            context.fail("file ends after " + std::to_string(f) + " of " +
                         std::to_string(num_faces) + " faces");
        }
        std::int64_t k = 0;
        if (!parse_integer(tokens[0], k) || k < 0 ||
            static_cast<std::size_t>(k) > tokens.size() - 1) {
            context.fail(at_line() + "malformed face");
        }
        corners.clear();
        for (std::int64_t c = 1; c <= k; ++c) {
            double index = 0;
            if (!parse_double(tokens[static_cast<std::size_t>(c)], index)) {
                context.fail(at_line() + "malformed face index");
            }
            corners.push_back(builder.checked_index(index));
        }
        builder.add_polygon(corners);
    }
    // More lines than the counts declare: a wrong count would silently drop faces.
    if (lines.next(tokens)) {
        context.fail(at_line() + "more data than the header's " + std::to_string(num_vertices) +
                     " vertices and " + std::to_string(num_faces) + " faces");
    }
    return builder.finish();
}

}  // namespace genflow::detail
