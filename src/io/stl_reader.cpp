// SPDX-License-Identifier: MIT
// STL, ascii ("solid ... facet normal ... outer loop / vertex x y z ... endsolid") and binary
// (80-byte header, uint32 count, 50 bytes per triangle). STL is a triangle soup: corners with
// bitwise-equal coordinates are welded into one vertex, in order of first appearance.
#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <string>
#include <unordered_map>

#include "io/readers.h"

namespace genflow::detail {

namespace {

struct PositionHash {
    std::size_t operator()(const std::array<std::uint64_t, 3>& key) const {
        std::size_t h = 1469598103934665603ULL;
        for (auto word : key) {
            h = (h ^ word) * 1099511628211ULL;
            h ^= h >> 29;
        }
        return h;
    }
};

// Welds corners with identical coordinates (+0 and -0 are the same corner).
class Welder {
public:
    explicit Welder(MeshBuilder& builder) : builder_(builder) {}

    std::int64_t index_of(double x, double y, double z) {
        const std::array<std::uint64_t, 3> key = {bits(x), bits(y), bits(z)};
        const auto [it, inserted] =
            index_.try_emplace(key, static_cast<std::int64_t>(builder_.num_vertices()));
        if (inserted) {
            builder_.add_vertex(x, y, z);
        }
        return it->second;
    }

private:
    static std::uint64_t bits(double value) {
        if (value == 0.0) {
            value = 0.0;
        }
        return std::bit_cast<std::uint64_t>(value);
    }
    MeshBuilder& builder_;
    std::unordered_map<std::array<std::uint64_t, 3>, std::int64_t, PositionHash> index_;
};

float read_float_le(const char* p) {
    std::array<unsigned char, 4> raw{};
    std::memcpy(raw.data(), p, 4);
    if constexpr (std::endian::native == std::endian::big) {
        std::reverse(raw.begin(), raw.end());
    }
    return std::bit_cast<float>(raw);
}

std::uint32_t triangle_count(std::string_view bytes) {
    std::array<unsigned char, 4> raw{};
    std::memcpy(raw.data(), bytes.data() + 80, 4);
    return static_cast<std::uint32_t>(raw[0]) | static_cast<std::uint32_t>(raw[1]) << 8 |
           static_cast<std::uint32_t>(raw[2]) << 16 | static_cast<std::uint32_t>(raw[3]) << 24;
}

TriangleMesh parse_binary_stl(std::string_view bytes, const ParseContext& context) {
    const std::uint32_t count = triangle_count(bytes);
    const std::uint64_t expected = 84 + 50 * static_cast<std::uint64_t>(count);
    if (expected != bytes.size()) {
        context.fail("binary STL header declares " + std::to_string(count) + " triangles (" +
                     std::to_string(expected) + " bytes) but the file has " +
                     std::to_string(bytes.size()) + " bytes");
    }
    MeshBuilder builder(context);
    builder.reserve(count / 2, count);
    Welder welder(builder);
    std::vector<std::int64_t> corners(3);
    std::size_t with_attribute = 0;  // faces whose attribute bytes are set: some writers' colours
    for (std::uint32_t t = 0; t < count; ++t) {
        const char* record = bytes.data() + 84 + 50 * static_cast<std::size_t>(t);
        for (int c = 0; c < 3; ++c) {
            const char* p = record + 12 + 12 * c;  // skip the facet normal
            corners[static_cast<std::size_t>(c)] =
                welder.index_of(read_float_le(p), read_float_le(p + 4), read_float_le(p + 8));
        }
        builder.add_polygon(corners);
        with_attribute += record[48] != 0 || record[49] != 0 ? 1 : 0;
    }
    if (with_attribute > 0) {
        context.warn(std::to_string(with_attribute) +
                     " faces' attribute bytes (face colours of some writers) left out");
    }
    return builder.finish();
}

TriangleMesh parse_ascii_stl(std::string_view bytes, const ParseContext& context) {
    TextScanner scanner(bytes);
    MeshBuilder builder(context);
    Welder welder(builder);
    std::vector<std::int64_t> corners;
    const auto expect = [&](std::string_view keyword) {
        const auto token = scanner.next_token();
        if (!iequals(token, keyword)) {
            context.fail("line " + std::to_string(scanner.line_number()) + ": expected '" +
                         std::string(keyword) + "', found '" + std::string(token.substr(0, 32)) +
                         "'");
        }
    };
    const auto number = [&] {
        double value = 0;
        const auto token = scanner.next_token();
        if (!parse_double(token, value)) {
            context.fail("line " + std::to_string(scanner.line_number()) + ": malformed number '" +
                         std::string(token.substr(0, 32)) + "'");
        }
        return value;
    };

    bool any_solid = false;
    for (auto token = scanner.next_token(); !token.empty(); token = scanner.next_token()) {
        if (!iequals(token, "solid")) {
            context.fail("line " + std::to_string(scanner.line_number()) + ": expected 'solid'");
        }
        any_solid = true;
        scanner.next_line();  // the solid's name, if any
        while (true) {
            token = scanner.next_token();
            if (token.empty()) {
                context.fail("file ends inside a solid (missing 'endsolid')");
            }
            if (iequals(token, "endsolid")) {
                scanner.next_line();
                break;
            }
            if (!iequals(token, "facet")) {
                context.fail("line " + std::to_string(scanner.line_number()) +
                             ": expected 'facet' or 'endsolid'");
            }
            expect("normal");
            for (int k = 0; k < 3; ++k) {
                (void)number();
            }
            expect("outer");
            expect("loop");
            corners.clear();
            for (token = scanner.next_token(); iequals(token, "vertex");
                 token = scanner.next_token()) {
                const double x = number();
                const double y = number();
                const double z = number();
                corners.push_back(welder.index_of(x, y, z));
            }
            if (!iequals(token, "endloop")) {
                context.fail("line " + std::to_string(scanner.line_number()) +
                             ": expected 'endloop'");
            }
            expect("endfacet");
            builder.add_polygon(corners);
        }
    }
    if (!any_solid) {
        context.fail("empty file");
    }
    return builder.finish();
}

bool starts_with_solid(std::string_view bytes) {
    TextScanner scanner(bytes);
    return iequals(scanner.next_token(), "solid");
}

// Ascii STL starts with "solid" and has a "facet" soon after; binary files whose 80-byte header
// happens to start with "solid" (many exporters write that) do not.
bool looks_like_ascii(std::string_view bytes) {
    if (!starts_with_solid(bytes)) {
        return false;
    }
    const std::string_view head = bytes.substr(0, 1024);
    TextScanner scanner(head);
    (void)scanner.next_line();  // "solid name"
    const auto token = scanner.next_token();
    return iequals(token, "facet") || iequals(token, "endsolid");
}

}  // namespace

TriangleMesh parse_stl(std::string_view bytes, const ParseContext& context) {
    if (bytes.empty()) {
        context.fail("empty file");
    }
    // Binary files may also start with "solid", so the size decides first.
    if (bytes.size() >= 84) {
        const std::uint64_t count = triangle_count(bytes);
        if (84 + 50 * count == bytes.size() || !looks_like_ascii(bytes)) {
            return parse_binary_stl(bytes, context);
        }
    }
    if (!starts_with_solid(bytes)) {
        context.fail("not an STL file (too short for binary, no 'solid' keyword)");
    }
    return parse_ascii_stl(bytes, context);
}

}  // namespace genflow::detail
