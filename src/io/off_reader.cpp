// SPDX-License-Identifier: MIT
// Object File Format (Geomview): "[ST][C][N]OFF", counts "nV nF nE", nV vertex lines
// "x y z [nx ny nz] [r g b [a]] [s t]" (the prefixes say which columns follow x y z), nF face
// lines "k i1 ... ik [colour]". Comments start with '#'.
#include <algorithm>
#include <cmath>
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

// The columns after x y z that the keyword's prefixes announce.
struct VertexColumns {
    bool normals = false;  // N
    bool colors = false;   // C
    bool texture = false;  // ST
};

VertexColumns columns_of(std::string_view keyword) {
    const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
    return {prefix.find('N') != std::string_view::npos, prefix.find('C') != std::string_view::npos,
            prefix.find("ST") != std::string_view::npos};
}

// A colour channel is an integer 0–255, or a fraction 0–1 when written with a point or exponent.
bool is_fraction(std::string_view token) {
    return token.find_first_of(".eE") != std::string_view::npos;
}

// What the vertex lines give beside x y z, read when asked for.
class VertexLineExtras {
public:
    VertexLineExtras(const VertexColumns& columns, std::int64_t vertices, VertexAttributes* out)
        : columns_(columns), out_(out) {
        if (out_ == nullptr) {
            return;
        }
        out_->normals.resize(columns.normals ? vertices : 0, 3);
        out_->colors.resize(columns.colors ? vertices : 0, 3);
        out_->uvs.resize(columns.texture ? vertices : 0, 2);
    }

    // The columns of vertex `i` after its x y z; false when they are not as announced.
    bool read(Eigen::Index i, const std::vector<std::string_view>& tokens) {
        if (out_ == nullptr) {
            return true;
        }
        std::size_t at = 3;
        double value = 0;
        for (int c = 0; columns_.normals && c < 3; ++c, ++at) {
            if (at >= tokens.size() || !parse_double(tokens[at], value)) {
                return false;
            }
            out_->normals(i, c) = value;
        }
        // r g b, or r g b a: whatever the texture coordinates leave.
        const std::size_t left = tokens.size() - std::min(tokens.size(), at);
        const std::size_t channels = left - (columns_.texture ? 2 : 0);
        if (columns_.colors && channels != 3 && channels != 4) {
            return false;
        }
        for (std::size_t c = 0; columns_.colors && c < channels; ++c, ++at) {
            if (!parse_double(tokens[at], value)) {
                return false;
            }
            if (c < 3) {
                out_->colors(i, static_cast<Eigen::Index>(c)) =
                    color_byte(value, is_fraction(tokens[at]));
            }
        }
        for (int c = 0; columns_.texture && c < 2; ++c, ++at) {
            if (at >= tokens.size() || !parse_double(tokens[at], value)) {
                return false;
            }
            out_->uvs(i, c) = value;
        }
        return true;
    }

private:
    VertexColumns columns_;
    VertexAttributes* out_;
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

TriangleMesh parse_off(std::string_view bytes, const ParseContext& context,
                       VertexAttributes* attributes) {
    OffLines lines(bytes);
    std::vector<std::string_view> tokens;
    const auto at_line = [&] { return "line " + std::to_string(lines.line_number()) + ": "; };

    if (!lines.next(tokens)) {
        context.fail("empty file");
    }
    const std::string keyword(tokens[0].substr(0, 32));
    if (!is_off_keyword(tokens[0])) {
        context.fail("not an OFF file (first word is '" + std::string(tokens[0].substr(0, 32)) +
                     "', expected OFF)");
    }
    if (tokens.size() > 1 && tokens[1] == "BINARY") {
        context.fail("binary OFF is not supported");
    }
    const VertexColumns columns = columns_of(tokens[0]);
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

    // n vertex lines take at least 6n - 1 bytes ("0 0 0", a newline between lines): no more
    // rows than that are kept, however many the counts declare.
    VertexLineExtras extras(
        columns,
        std::min<std::int64_t>(num_vertices, static_cast<std::int64_t>(lines.bytes_left() / 6 + 1)),
        attributes);
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
        if (!extras.read(static_cast<Eigen::Index>(i), tokens)) {
            context.fail(at_line() + "the vertex lacks the columns '" + std::string(keyword) +
                         "' announces");
        }
    }
    std::vector<std::int64_t> corners;
    std::size_t face_colors = 0;
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
        face_colors += tokens.size() > static_cast<std::size_t>(k) + 1 ? 1 : 0;
    }
    if (face_colors > 0 && attributes != nullptr) {
        context.warn(std::to_string(face_colors) + " face colours left out");
    }
    // More lines than the counts declare: a wrong count would silently drop faces.
    if (lines.next(tokens)) {
        context.fail(at_line() + "more data than the header's " + std::to_string(num_vertices) +
                     " vertices and " + std::to_string(num_faces) + " faces");
    }
    return builder.finish();
}

}  // namespace genflow::detail
