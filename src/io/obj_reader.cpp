// SPDX-License-Identifier: MIT
// Wavefront OBJ: only `v` (with its colour, if any) and `f` records matter to us. We parse them
// ourselves rather than with tinyobjloader (Debian's libtinyobjloader-dev) because that library
// turns unparsable coordinates such as "nan" or "1.0x" silently into 0, which would hide corrupt
// input.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "io/readers.h"

namespace genflow::detail {

namespace {

// An `f` corner is "i", "i/t", "i//n" or "i/t/n"; only i matters. Negative i counts back from
// the last vertex defined so far (OBJ's relative indices); 0 is invalid.
std::int64_t corner_index(std::string_view token, std::size_t defined_vertices,
                          const ParseContext& context, std::size_t line) {
    const auto slash = token.find('/');
    const auto head = token.substr(0, slash);
    std::int64_t index = 0;
    if (!parse_integer(head, index) || index == 0) {
        context.fail("line " + std::to_string(line) + ": bad face corner '" + std::string(token) +
                     "'");
    }
    const auto n = static_cast<std::int64_t>(defined_vertices);
    const std::int64_t zero_based = index > 0 ? index - 1 : n + index;
    if (zero_based > std::numeric_limits<int>::max() ||
        zero_based < std::numeric_limits<int>::min()) {
        context.fail("line " + std::to_string(line) + ": face index " + std::string(head) +
                     " is out of range");
    }
    return zero_based;
}

// A colour channel given as 0–1, as a byte.
std::uint8_t unit_to_byte(double value) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(255 * value, 0.0, 255.0)));
}

}  // namespace

TriangleMesh parse_obj(std::string_view bytes, const ParseContext& context,
                       VertexAttributes* attributes) {
    MeshBuilder builder(context);
    std::vector<std::array<std::uint8_t, 3>> colors;  // of the `v` records that have one
    std::size_t skipped = 0;                          // vt and vn records
    TextScanner scanner(bytes);
    std::vector<std::int64_t> corners;
    std::vector<std::string_view> tokens;
    std::size_t line_number = 0;
    while (!scanner.at_end()) {
        const std::string_view line = scanner.next_line();
        ++line_number;
        split_tokens(line.substr(0, line.find('#')), tokens);
        if (tokens.empty()) {
            continue;
        }
        if (tokens[0] == "v") {
            double xyz[3];
            // A `v` record may carry a fourth (w) coordinate or a colour after x y z.
            if (tokens.size() < 4 || !parse_double(tokens[1], xyz[0]) ||
                !parse_double(tokens[2], xyz[1]) || !parse_double(tokens[3], xyz[2])) {
                context.fail("line " + std::to_string(line_number) + ": malformed vertex '" +
                             std::string(line) + "'");
            }
            builder.add_vertex(xyz[0], xyz[1], xyz[2]);
            double rgb[3];
            if (tokens.size() == 7 && parse_double(tokens[4], rgb[0]) &&
                parse_double(tokens[5], rgb[1]) && parse_double(tokens[6], rgb[2])) {
                colors.push_back(
                    {unit_to_byte(rgb[0]), unit_to_byte(rgb[1]), unit_to_byte(rgb[2])});
            }
        } else if (tokens[0] == "vt" || tokens[0] == "vn") {
            ++skipped;
        } else if (tokens[0] == "f") {
            corners.clear();
            for (std::size_t k = 1; k < tokens.size(); ++k) {
                corners.push_back(
                    corner_index(tokens[k], builder.num_vertices(), context, line_number));
            }
            builder.add_polygon(corners);
        }
        // Everything else (g, o, s, usemtl, mtllib, l, p, ...) carries nothing we keep.
    }
    if (skipped > 0) {
        context.warn(std::to_string(skipped) +
                     " texture coordinate and normal records (vt, vn) left out");
    }
    if (attributes != nullptr && !colors.empty()) {
        if (colors.size() != builder.num_vertices()) {
            context.warn("vertex colours on some vertices only, left out");
        } else {
            attributes->colors.resize(static_cast<Eigen::Index>(colors.size()), 3);
            for (std::size_t i = 0; i < colors.size(); ++i) {
                for (std::size_t c = 0; c < 3; ++c) {
                    attributes->colors(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) =
                        colors[i][c];
                }
            }
        }
    }
    return builder.finish();
}

}  // namespace genflow::detail
