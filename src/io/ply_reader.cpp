// SPDX-License-Identifier: MIT
// Stanford PLY 1.0, ascii and binary in either byte order. We keep the x, y, z properties of
// the `vertex` element and the vertex-index list of the `face` element, and skip every other
// element and property by its declared type. Debian ships no PLY parser library (happly,
// tinyply and rply are not packaged), so this one is ours and is fuzzed (fuzz/ply_fuzz.cpp).
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>

#include "io/readers.h"

namespace genflow::detail {

namespace {

enum class Encoding { Ascii, BinaryLittleEndian, BinaryBigEndian };
enum class ScalarType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<ScalarType> scalar_type(std::string_view name) {
    if (name == "char" || name == "int8")
        return ScalarType::Int8;
    if (name == "uchar" || name == "uint8")
        return ScalarType::UInt8;
    if (name == "short" || name == "int16")
        return ScalarType::Int16;
    if (name == "ushort" || name == "uint16")
        return ScalarType::UInt16;
    if (name == "int" || name == "int32")
        return ScalarType::Int32;
    if (name == "uint" || name == "uint32")
        return ScalarType::UInt32;
    if (name == "float" || name == "float32")
        return ScalarType::Float32;
    if (name == "double" || name == "float64")
        return ScalarType::Float64;
    return std::nullopt;
}

std::size_t byte_size(ScalarType type) {
    switch (type) {
        case ScalarType::Int8:
        case ScalarType::UInt8:
            return 1;
        case ScalarType::Int16:
        case ScalarType::UInt16:
            return 2;
        case ScalarType::Int32:
        case ScalarType::UInt32:
        case ScalarType::Float32:
            return 4;
        case ScalarType::Float64:
            return 8;
    }
    return 1;
}

bool is_integer_type(ScalarType type) {
    return type != ScalarType::Float32 && type != ScalarType::Float64;
}

struct Property {
    std::string name;
    ScalarType type = ScalarType::Float32;
    bool is_list = false;
    ScalarType count_type = ScalarType::UInt8;
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
};

struct Header {
    Encoding encoding = Encoding::Ascii;
    std::vector<Element> elements;
    std::size_t data_offset = 0;
};

Header parse_header(std::string_view bytes, const ParseContext& context) {
    TextScanner scanner(bytes);
    if (scanner.next_line() != "ply") {
        context.fail("not a PLY file (missing 'ply' magic line)");
    }
    Header header;
    bool has_format = false;
    std::size_t line_number = 1;
    std::vector<std::string_view> tokens;
    while (true) {
        if (scanner.at_end()) {
            context.fail("header has no 'end_header' line");
        }
        split_tokens(scanner.next_line(), tokens);
        ++line_number;
        const auto at_line = "header line " + std::to_string(line_number) + ": ";
        if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") {
            continue;
        }
        if (tokens[0] == "end_header") {
            header.data_offset = scanner.position();
            break;
        }
        if (tokens[0] == "format") {
            if (tokens.size() < 3 || tokens[2] != "1.0") {
                context.fail(at_line + "unsupported format line");
            }
            if (tokens[1] == "ascii") {
                header.encoding = Encoding::Ascii;
            } else if (tokens[1] == "binary_little_endian") {
                header.encoding = Encoding::BinaryLittleEndian;
            } else if (tokens[1] == "binary_big_endian") {
                header.encoding = Encoding::BinaryBigEndian;
            } else {
                context.fail(at_line + "unknown format '" + std::string(tokens[1]) + "'");
            }
            has_format = true;
        } else if (tokens[0] == "element") {
            std::int64_t count = 0;
            if (tokens.size() != 3 || !parse_integer(tokens[2], count) || count < 0) {
                context.fail(at_line + "malformed element line");
            }
            header.elements.push_back(
                {std::string(tokens[1]), static_cast<std::uint64_t>(count), {}});
        } else if (tokens[0] == "property") {
            if (header.elements.empty()) {
                context.fail(at_line + "property before any element");
            }
            Property property;
            if (tokens.size() == 5 && tokens[1] == "list") {
                const auto count_type = scalar_type(tokens[2]);
                const auto item_type = scalar_type(tokens[3]);
                if (!count_type || !item_type || !is_integer_type(*count_type)) {
                    context.fail(at_line + "malformed list property");
                }
                property = {std::string(tokens[4]), *item_type, true, *count_type};
            } else if (tokens.size() == 3) {
                const auto type = scalar_type(tokens[1]);
                if (!type) {
                    context.fail(at_line + "unknown property type '" + std::string(tokens[1]) +
                                 "'");
                }
                property = {std::string(tokens[2]), *type, false, ScalarType::UInt8};
            } else {
                context.fail(at_line + "malformed property line");
            }
            header.elements.back().properties.push_back(std::move(property));
        } else {
            context.fail(at_line + "unknown keyword '" + std::string(tokens[0].substr(0, 32)) +
                         "'");
        }
    }
    if (!has_format) {
        context.fail("header has no 'format' line");
    }
    return header;
}

// Reads property values one at a time, from text or binary data, never past the end.
class ValueReader {
public:
    ValueReader(std::string_view data, Encoding encoding, const ParseContext& context)
        : data_(data), encoding_(encoding), context_(context), text_(data) {}

    [[nodiscard]] std::size_t bytes_left() const {
        return encoding_ == Encoding::Ascii ? text_.bytes_left() : data_.size() - pos_;
    }

    /// Whether anything but whitespace is left after the values read.
    [[nodiscard]] bool content_left() {
        if (encoding_ == Encoding::Ascii) {
            return !text_.next_token().empty();
        }
        const std::string_view rest = data_.substr(pos_);
        return rest.find_first_not_of(" \t\r\n") != std::string_view::npos;
    }

    /// Reads one value of `type`; `element` names what is being read in error messages.
    double read(ScalarType type, const std::string& element) {
        if (encoding_ == Encoding::Ascii) {
            const auto token = text_.next_token();
            double value = 0;
            if (token.empty()) {
                context_.fail("file ends while reading element '" + element + "'");
            }
            if (!parse_double(token, value)) {
                context_.fail("malformed number '" + std::string(token.substr(0, 32)) +
                              "' in element '" + element + "'");
            }
            return value;
        }
        const std::size_t size = byte_size(type);
        if (data_.size() - pos_ < size) {
            context_.fail("file ends while reading element '" + element +
                          "' (truncated binary data)");
        }
        std::array<unsigned char, 8> raw{};
        std::memcpy(raw.data(), data_.data() + pos_, size);
        pos_ += size;
        const bool file_is_little = encoding_ == Encoding::BinaryLittleEndian;
        if (file_is_little != (std::endian::native == std::endian::little)) {
            std::reverse(raw.begin(), raw.begin() + static_cast<std::ptrdiff_t>(size));
        }
        return decode(type, raw.data());
    }

private:
    static double decode(ScalarType type, const unsigned char* raw) {
        switch (type) {
            case ScalarType::Int8:
                return as<std::int8_t>(raw);
            case ScalarType::UInt8:
                return as<std::uint8_t>(raw);
            case ScalarType::Int16:
                return as<std::int16_t>(raw);
            case ScalarType::UInt16:
                return as<std::uint16_t>(raw);
            case ScalarType::Int32:
                return as<std::int32_t>(raw);
            case ScalarType::UInt32:
                return as<std::uint32_t>(raw);
            case ScalarType::Float32:
                return as<float>(raw);
            case ScalarType::Float64:
                return as<double>(raw);
        }
        return 0;
    }
    template <typename T>
    static double as(const unsigned char* raw) {
        T value;
        std::memcpy(&value, raw, sizeof(T));
        return static_cast<double>(value);
    }

    std::string_view data_;
    std::size_t pos_ = 0;
    Encoding encoding_;
    const ParseContext& context_;
    TextScanner text_;
};

std::size_t min_bytes_per_instance(const Element& element, Encoding encoding) {
    std::size_t bytes = 0;
    for (const auto& property : element.properties) {
        // Text needs a digit and a separator per value; binary the declared size.
        bytes += encoding == Encoding::Ascii
                     ? 2
                     : byte_size(property.is_list ? property.count_type : property.type);
    }
    return bytes;
}

// A vertex property holding a normal component: nx, ny, nz, or normal_x, … as PCL names them.
int normal_axis(std::string_view name) {
    for (int axis = 0; axis < 3; ++axis) {
        const char letter = "xyz"[axis];
        if (name == std::string{'n', letter} || name == std::string("normal_") + letter) {
            return axis;
        }
    }
    return -1;
}

}  // namespace

TriangleMesh parse_ply(std::string_view bytes, const ParseContext& context,
                       Eigen::MatrixX3d* vertex_normals) {
    const Header header = parse_header(bytes, context);
    ValueReader reader(bytes.substr(header.data_offset), header.encoding, context);
    MeshBuilder builder(context);
    bool has_vertices = false;
    std::vector<std::int64_t> corners;
    std::vector<Eigen::Vector3d> normals;

    for (const auto& element : header.elements) {
        const bool is_vertex = element.name == "vertex";
        const bool is_face = element.name == "face";
        int x = -1;
        int y = -1;
        int z = -1;
        int indices = -1;
        std::array<int, 3> normal = {-1, -1, -1};
        for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
            const auto& property = element.properties[static_cast<std::size_t>(p)];
            if (is_vertex && !property.is_list) {
                x = property.name == "x" ? p : x;
                y = property.name == "y" ? p : y;
                z = property.name == "z" ? p : z;
                if (const int axis = normal_axis(property.name); axis >= 0) {
                    normal[static_cast<std::size_t>(axis)] = p;
                }
            }
            if (is_face && property.is_list &&
                (property.name == "vertex_indices" || property.name == "vertex_index" ||
                 indices < 0)) {
                indices = p;
            }
        }
        if (is_vertex && (x < 0 || y < 0 || z < 0)) {
            context.fail("element 'vertex' lacks an x, y or z property");
        }
        if (is_face && indices < 0) {
            context.fail("element 'face' has no vertex index list");
        }
        if (!is_vertex && !is_face && element.count > 0) {
            context.warn("element '" + element.name + "' ignored");
        }
        const std::size_t min_bytes = min_bytes_per_instance(element, header.encoding);
        if (min_bytes > 0 && element.count > reader.bytes_left() / min_bytes) {
            context.fail("element '" + element.name + "' declares " +
                         std::to_string(element.count) +
                         " items, more than the file can hold (truncated?)");
        }
        const bool with_normals = is_vertex && vertex_normals != nullptr &&
                                  std::ranges::none_of(normal, [](int p) { return p < 0; });
        if (is_vertex) {
            builder.reserve(static_cast<std::size_t>(element.count), 0);
            has_vertices = true;
            normals.clear();
        }
        if (element.properties.empty()) {
            continue;  // nothing to read, however many items it declares
        }

        double xyz[3] = {0, 0, 0};
        double nxyz[3] = {0, 0, 0};
        for (std::uint64_t i = 0; i < element.count; ++i) {
            corners.clear();
            for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
                const auto& property = element.properties[static_cast<std::size_t>(p)];
                if (!property.is_list) {
                    const double value = reader.read(property.type, element.name);
                    if (p == x)
                        xyz[0] = value;
                    if (p == y)
                        xyz[1] = value;
                    if (p == z)
                        xyz[2] = value;
                    for (int axis = 0; axis < 3; ++axis) {
                        if (with_normals && p == normal[static_cast<std::size_t>(axis)]) {
                            nxyz[axis] = value;
                        }
                    }
                    continue;
                }
                const double count = reader.read(property.count_type, element.name);
                // Count types are integers, so the value is exact; in ascii it may be anything.
                if (!std::isfinite(count) || count < 0 || count != std::floor(count) ||
                    count > static_cast<double>(reader.bytes_left())) {
                    context.fail("invalid list length in element '" + element.name + "'");
                }
                for (std::int64_t k = 0; k < static_cast<std::int64_t>(count); ++k) {
                    const double value = reader.read(property.type, element.name);
                    if (is_face && p == indices) {
                        corners.push_back(builder.checked_index(value));
                    }
                }
            }
            if (is_vertex) {
                builder.add_vertex(xyz[0], xyz[1], xyz[2]);
                if (with_normals) {
                    normals.emplace_back(nxyz[0], nxyz[1], nxyz[2]);
                }
            } else if (is_face) {
                builder.add_polygon(corners);
            }
        }
    }
    if (!has_vertices) {
        context.fail("no 'vertex' element");
    }
    // Data beyond the declared elements: a wrong count would silently drop what follows.
    if (reader.content_left()) {
        context.fail("more data than the header declares");
    }
    if (vertex_normals != nullptr) {
        vertex_normals->resize(static_cast<Eigen::Index>(normals.size()), 3);
        for (std::size_t i = 0; i < normals.size(); ++i) {
            vertex_normals->row(static_cast<Eigen::Index>(i)) = normals[i].transpose();
        }
    }
    return builder.finish();
}

}  // namespace genflow::detail
