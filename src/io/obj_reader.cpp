// SPDX-License-Identifier: MIT
// Wavefront OBJ: `v` (with its colour, if any), `vt`, `vn` and `f` records matter to us. We
// parse them ourselves rather than with tinyobjloader (Debian's libtinyobjloader-dev) because
// that library turns unparsable coordinates such as "nan" or "1.0x" silently into 0, which
// would hide corrupt input.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "io/corner_data.h"
#include "io/readers.h"

namespace genflow::detail {

namespace {

// An index of an `f` corner into records defined so far (`defined`): 1-based, or negative to
// count back from the last (OBJ's relative indices); 0 is invalid.
std::int64_t record_index(std::string_view token, std::string_view corner, std::size_t defined,
                          const ParseContext& context, std::size_t line) {
    std::int64_t index = 0;
    if (!parse_integer(token, index) || index == 0) {
        context.fail("line " + std::to_string(line) + ": bad face corner '" + std::string(corner) +
                     "'");
    }
    const auto n = static_cast<std::int64_t>(defined);
    const std::int64_t zero_based = index > 0 ? index - 1 : n + index;
    if (zero_based > std::numeric_limits<int>::max() ||
        zero_based < std::numeric_limits<int>::min()) {
        context.fail("line " + std::to_string(line) + ": face index " + std::string(token) +
                     " is out of range");
    }
    return zero_based;
}

// What the records of one kind (vt or vn) give: their rows and, per face corner, which.
struct CornerRecords {
    std::vector<double> rows;    // `width` numbers per record
    std::vector<int> triangles;  // per face corner, a record index (from the fan split)
    std::size_t faces_with = 0;  // polygons whose corners all name one
    std::size_t faces_without = 0;
    std::vector<std::int64_t> polygon;

    [[nodiscard]] std::size_t count(int width) const {
        return rows.size() / static_cast<std::size_t>(width);
    }
};

// A `vt u [v [w]]` or `vn x y z` record's numbers: the first `width` (missing ones 0).
void add_record(CornerRecords& records, const std::vector<std::string_view>& tokens, int width,
                const ParseContext& context, std::size_t line) {
    for (int k = 0; k < width; ++k) {
        double value = 0;
        const auto at = static_cast<std::size_t>(k) + 1;
        if ((at < tokens.size() && !parse_double(tokens[at], value)) || !std::isfinite(value) ||
            (at >= tokens.size() && k == 0)) {
            context.fail("line " + std::to_string(line) + ": malformed " + std::string(tokens[0]) +
                         " record");
        }
        records.rows.push_back(value);
    }
}

// Per face, the corner rows of `records` when every polygon named one at each corner and
// their values agree per vertex (kept then per vertex) or not (kept per corner, for texture
// coordinates); a warning says what is left out otherwise.
struct Settled {
    std::optional<Eigen::MatrixXd> per_vertex;
    Eigen::MatrixXd table;
    Eigen::MatrixX3i corners;
};

std::optional<Settled> settle(const CornerRecords& records, int width, const TriangleMesh& mesh,
                              const char* what, const ParseContext& context) {
    if (records.count(width) == 0 && records.faces_with == 0) {
        return std::nullopt;
    }
    if (records.faces_with == 0 || records.faces_without > 0) {
        context.warn(std::string(what) +
                     (records.faces_with == 0 ? " that no face uses" : " on some faces only") +
                     ", left out");
        return std::nullopt;
    }
    Settled settled;
    settled.table =
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            records.rows.data(), static_cast<Eigen::Index>(records.count(width)), width);
    settled.corners = as_faces(records.triangles);
    settled.per_vertex = per_vertex_rows(mesh.F, settled.table, settled.corners, mesh.V.rows());
    return settled;
}

void store_texture(const std::optional<Settled>& texture, VertexAttributes& attributes) {
    if (!texture) {
        return;
    }
    store_texture_coordinates(texture->per_vertex, texture->table, texture->corners, attributes);
}

void store_normals(const std::optional<Settled>& normals, VertexAttributes& attributes,
                   const ParseContext& context) {
    if (!normals) {
        return;
    }
    if (normals->per_vertex) {
        attributes.normals = *normals->per_vertex;
    } else {
        context.warn("normals (vn) that differ between a vertex's corners, left out");
    }
}

void store_colors(const std::vector<std::array<std::uint8_t, 3>>& colors, std::size_t vertex_count,
                  VertexAttributes& attributes, const ParseContext& context) {
    if (colors.empty()) {
        return;
    }
    if (colors.size() != vertex_count) {
        context.warn("vertex colours on some vertices only, left out");
        return;
    }
    attributes.colors.resize(static_cast<Eigen::Index>(colors.size()), 3);
    for (std::size_t i = 0; i < colors.size(); ++i) {
        for (std::size_t c = 0; c < 3; ++c) {
            attributes.colors(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) =
                colors[i][c];
        }
    }
}

// The texture and normal records an `f` record's corners name ("i", "i/t", "i//n", "i/t/n").
void add_corner_records(std::string_view corner, CornerRecords& texture, CornerRecords& normals,
                        const ParseContext& context, std::size_t line) {
    const std::size_t first = corner.find('/');
    if (first == std::string_view::npos) {
        return;
    }
    const std::size_t second = corner.find('/', first + 1);
    const std::string_view t = corner.substr(
        first + 1, second == std::string_view::npos ? std::string_view::npos : second - first - 1);
    if (!t.empty()) {
        texture.polygon.push_back(record_index(t, corner, texture.count(2), context, line));
    }
    if (second != std::string_view::npos) {
        normals.polygon.push_back(
            record_index(corner.substr(second + 1), corner, normals.count(3), context, line));
    }
}

// After a polygon: its corner records as fan triangles, if it named one at every corner.
void close_polygon(CornerRecords& records, std::size_t corners, int width,
                   const ParseContext& context, std::size_t line) {
    if (records.polygon.size() == corners && corners >= 3) {
        for (const std::int64_t index : records.polygon) {
            if (index < 0 || index >= static_cast<std::int64_t>(records.count(width))) {
                context.fail("line " + std::to_string(line) + ": a face corner names a " +
                             (width == 2 ? "vt" : "vn") + " record that is not defined");
            }
        }
        append_fan(records.polygon, records.triangles);
        ++records.faces_with;
    } else if (corners >= 3) {
        ++records.faces_without;
    }
    records.polygon.clear();
}

}  // namespace

TriangleMesh parse_obj(std::string_view bytes, const ParseContext& context,
                       VertexAttributes* attributes) {
    MeshBuilder builder(context);
    std::vector<std::array<std::uint8_t, 3>> colors;  // of the `v` records that have one
    CornerRecords texture;
    CornerRecords normals;
    bool materials = false;
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
                    {color_byte(rgb[0], true), color_byte(rgb[1], true), color_byte(rgb[2], true)});
            }
        } else if (tokens[0] == "vt") {
            add_record(texture, tokens, 2, context, line_number);
        } else if (tokens[0] == "vn") {
            add_record(normals, tokens, 3, context, line_number);
        } else if (tokens[0] == "f") {
            corners.clear();
            for (std::size_t k = 1; k < tokens.size(); ++k) {
                const std::string_view corner = tokens[k];
                corners.push_back(record_index(corner.substr(0, corner.find('/')), corner,
                                               builder.num_vertices(), context, line_number));
                add_corner_records(corner, texture, normals, context, line_number);
            }
            builder.add_polygon(corners);
            close_polygon(texture, corners.size(), 2, context, line_number);
            close_polygon(normals, corners.size(), 3, context, line_number);
        } else if (tokens[0] == "mtllib") {
            materials = true;
        }
        // Everything else (g, o, s, usemtl, l, p, ...) carries nothing we keep.
    }
    TriangleMesh mesh = builder.finish();
    if (attributes != nullptr) {
        if (materials) {
            context.warn("its material library (mtllib) is left out: outputs name no material");
        }
        store_colors(colors, builder.num_vertices(), *attributes, context);
        store_texture(settle(texture, 2, mesh, "texture coordinates (vt)", context), *attributes);
        store_normals(settle(normals, 3, mesh, "normals (vn)", context), *attributes, context);
    }
    return mesh;
}

}  // namespace genflow::detail
