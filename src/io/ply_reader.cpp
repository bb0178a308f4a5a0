// SPDX-License-Identifier: MIT
// Stanford PLY 1.0, ascii and binary in either byte order. We keep the x, y, z properties of
// the `vertex` element and the vertex-index list of the `face` element, and, when asked, the
// vertex element's other single properties (normals, colours, texture coordinates, named
// values) and the face element's `texcoord` list (texture coordinates per corner); every other
// element and property is skipped by its declared type. Debian ships no PLY parser library (happly,
// tinyply and rply are not packaged), so this one is ours and is fuzzed (fuzz/ply_fuzz.cpp).
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>

#include "io/corner_data.h"
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

// A vertex property holding a texture coordinate: u, v; s, t; or texture_u, texture_v
// (MeshLab), as Blender and MeshLab read them.
int texture_axis(std::string_view name) {
    if (name == "u" || name == "s" || name == "texture_u") {
        return 0;
    }
    return name == "v" || name == "t" || name == "texture_v" ? 1 : -1;
}

// A vertex property holding a colour channel: red, green, blue, or diffuse_red, … (Blender).
int color_channel(std::string_view name) {
    if (name.starts_with("diffuse_")) {
        name.remove_prefix(8);
    }
    return name == "red" ? 0 : name == "green" ? 1 : name == "blue" ? 2 : -1;
}

// Where the vertex element keeps what rides along with its positions (property indices), and
// what it reads of them; a triple counts only when all three are there.
struct VertexExtras {
    std::array<int, 3> normal = {-1, -1, -1};
    std::array<int, 3> color = {-1, -1, -1};
    std::array<int, 2> uv = {-1, -1};
    bool float_color = false;  // 0–1 floats rather than 0–255 integers
    std::vector<int> values;   // every other single property: a named value per vertex
    std::vector<Eigen::Vector3d> normals;
    std::vector<std::array<std::uint8_t, 3>> colors;
    std::vector<Eigen::Vector2d> uvs;
    std::vector<std::vector<double>> value_rows;  // per value, per vertex

    template <std::size_t N>
    static bool complete(const std::array<int, N>& indices) {
        return std::ranges::none_of(indices, [](int p) { return p < 0; });
    }
};

VertexExtras vertex_extras(const Element& element, const ParseContext& context) {
    VertexExtras extras;
    for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
        const Property& property = element.properties[static_cast<std::size_t>(p)];
        if (property.is_list) {
            context.warn("vertex property list '" + property.name + "' left out");
        } else if (const int axis = normal_axis(property.name); axis >= 0) {
            extras.normal[static_cast<std::size_t>(axis)] = p;
        } else if (const int channel = color_channel(property.name); channel >= 0) {
            extras.color[static_cast<std::size_t>(channel)] = p;
            extras.float_color = !is_integer_type(property.type);
        } else if (const int coordinate = texture_axis(property.name);
                   coordinate >= 0 && extras.uv[static_cast<std::size_t>(coordinate)] < 0) {
            extras.uv[static_cast<std::size_t>(coordinate)] = p;
        } else if (property.name != "x" && property.name != "y" && property.name != "z") {
            extras.values.push_back(p);
        }
    }
    // A lone component is a value of its own, not part of a normal, a colour or a texture
    // coordinate.
    const auto keep_lone = [&](auto& indices) {
        if (!VertexExtras::complete(indices)) {
            for (const int p : indices) {
                if (p >= 0) {
                    extras.values.push_back(p);
                }
            }
            indices.fill(-1);
        }
    };
    keep_lone(extras.normal);
    keep_lone(extras.color);
    keep_lone(extras.uv);
    std::ranges::sort(extras.values);
    extras.value_rows.resize(extras.values.size());
    return extras;
}

// Keeps vertex `row`'s extras (`values`: the row's single properties, by property index).
void keep_extras(VertexExtras& extras, const std::vector<double>& values) {
    if (VertexExtras::complete(extras.normal)) {
        extras.normals.emplace_back(values[static_cast<std::size_t>(extras.normal[0])],
                                    values[static_cast<std::size_t>(extras.normal[1])],
                                    values[static_cast<std::size_t>(extras.normal[2])]);
    }
    if (VertexExtras::complete(extras.color)) {
        std::array<std::uint8_t, 3> color{};
        for (std::size_t c = 0; c < 3; ++c) {
            color[c] =
                color_byte(values[static_cast<std::size_t>(extras.color[c])], extras.float_color);
        }
        extras.colors.push_back(color);
    }
    if (VertexExtras::complete(extras.uv)) {
        extras.uvs.emplace_back(values[static_cast<std::size_t>(extras.uv[0])],
                                values[static_cast<std::size_t>(extras.uv[1])]);
    }
    for (std::size_t k = 0; k < extras.values.size(); ++k) {
        extras.value_rows[k].push_back(values[static_cast<std::size_t>(extras.values[k])]);
    }
}

void store_extras(const VertexExtras& extras, const Element& vertex, VertexAttributes& out) {
    out.normals.resize(static_cast<Eigen::Index>(extras.normals.size()), 3);
    for (std::size_t i = 0; i < extras.normals.size(); ++i) {
        out.normals.row(static_cast<Eigen::Index>(i)) = extras.normals[i].transpose();
    }
    out.colors.resize(static_cast<Eigen::Index>(extras.colors.size()), 3);
    for (std::size_t i = 0; i < extras.colors.size(); ++i) {
        for (std::size_t c = 0; c < 3; ++c) {
            out.colors(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) =
                extras.colors[i][c];
        }
    }
    out.uvs.resize(static_cast<Eigen::Index>(extras.uvs.size()), 2);
    for (std::size_t i = 0; i < extras.uvs.size(); ++i) {
        out.uvs.row(static_cast<Eigen::Index>(i)) = extras.uvs[i].transpose();
    }
    out.scalars.clear();
    for (std::size_t k = 0; k < extras.values.size(); ++k) {
        const std::vector<double>& rows = extras.value_rows[k];
        out.scalars.emplace_back(
            vertex.properties[static_cast<std::size_t>(extras.values[k])].name,
            Eigen::Map<const Eigen::VectorXd>(rows.data(), static_cast<Eigen::Index>(rows.size())));
    }
}

// The face properties genflow does not keep (per-face colours, normals, values), named in one
// warning.
void warn_left_out_face_properties(const Element& face, int indices, int texcoord,
                                   const ParseContext& context) {
    std::string names;
    for (int p = 0; p < static_cast<int>(face.properties.size()); ++p) {
        if (p != indices && p != texcoord) {
            names +=
                (names.empty() ? "" : ", ") + face.properties[static_cast<std::size_t>(p)].name;
        }
    }
    if (!names.empty()) {
        context.warn("face properties left out: " + names);
    }
}

// A face element's `texcoord` list (MeshLab's texture coordinates per corner: u, v for each
// of the face's corners), kept beside the fan split of its vertex indices.
struct FaceTexture {
    int property = -1;           // the list's index among the face's properties
    std::vector<double> values;  // of the face being read
    std::vector<double> table;   // u, v per corner of every face
    std::vector<int> triangles;  // per fan triangle corner, its table row
    std::vector<std::int64_t> polygon;
    std::size_t faces_with = 0;
    std::size_t faces_without = 0;

    // After a face: its corners' rows, if it gave u, v for each corner.
    void close_face(std::size_t corners) {
        if (property >= 0 && corners >= 3) {
            if (values.size() == 2 * corners) {
                polygon.clear();
                for (std::size_t k = 0; k < corners; ++k) {
                    polygon.push_back(static_cast<std::int64_t>(table.size() / 2));
                    table.push_back(values[2 * k]);
                    table.push_back(values[2 * k + 1]);
                }
                append_fan(polygon, triangles);
                ++faces_with;
            } else {
                ++faces_without;
            }
        }
        values.clear();
    }

    // Per vertex where no seam splits a vertex's coordinates, else per corner.
    void store(const TriangleMesh& mesh, VertexAttributes& out, const ParseContext& context) const {
        if (faces_with == 0) {
            return;
        }
        if (faces_without > 0) {
            context.warn("face texture coordinates (texcoord) on some faces only, left out");
            return;
        }
        const Eigen::MatrixXd rows =
            Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>>(
                table.data(), static_cast<Eigen::Index>(table.size() / 2), 2);
        const Eigen::MatrixX3i corners = as_faces(triangles);
        store_texture_coordinates(per_vertex_rows(mesh.F, rows, corners, mesh.V.rows()), rows,
                                  corners, out);
    }
};

}  // namespace

TriangleMesh parse_ply(std::string_view bytes, const ParseContext& context,
                       VertexAttributes* attributes) {
    const Header header = parse_header(bytes, context);
    ValueReader reader(bytes.substr(header.data_offset), header.encoding, context);
    MeshBuilder builder(context);
    const Element* vertex_element = nullptr;
    std::vector<std::int64_t> corners;
    std::vector<double> values;  // a vertex's single properties, by property index
    VertexExtras extras;
    FaceTexture texture;

    for (const auto& element : header.elements) {
        const bool is_vertex = element.name == "vertex";
        const bool is_face = element.name == "face";
        int x = -1;
        int y = -1;
        int z = -1;
        int indices = -1;
        for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
            const auto& property = element.properties[static_cast<std::size_t>(p)];
            if (is_vertex && !property.is_list) {
                x = property.name == "x" ? p : x;
                y = property.name == "y" ? p : y;
                z = property.name == "z" ? p : z;
            }
            if (is_face && property.is_list && property.name == "texcoord" &&
                attributes != nullptr) {
                texture.property = p;
            } else if (is_face && property.is_list &&
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
        if (is_face && attributes != nullptr) {
            warn_left_out_face_properties(element, indices, texture.property, context);
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
        const bool with_extras = is_vertex && attributes != nullptr;
        if (is_vertex) {
            builder.reserve(static_cast<std::size_t>(element.count), 0);
            vertex_element = &element;
            extras = with_extras ? vertex_extras(element, context) : VertexExtras{};
        }
        if (element.properties.empty()) {
            continue;  // nothing to read, however many items it declares
        }

        values.assign(element.properties.size(), 0);
        for (std::uint64_t i = 0; i < element.count; ++i) {
            corners.clear();
            for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
                const auto& property = element.properties[static_cast<std::size_t>(p)];
                if (!property.is_list) {
                    values[static_cast<std::size_t>(p)] = reader.read(property.type, element.name);
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
                    } else if (is_face && p == texture.property) {
                        texture.values.push_back(value);
                    }
                }
            }
            if (is_vertex) {
                builder.add_vertex(values[static_cast<std::size_t>(x)],
                                   values[static_cast<std::size_t>(y)],
                                   values[static_cast<std::size_t>(z)]);
                if (with_extras) {
                    keep_extras(extras, values);
                }
            } else if (is_face) {
                builder.add_polygon(corners);
                texture.close_face(corners.size());
            }
        }
    }
    if (vertex_element == nullptr) {
        context.fail("no 'vertex' element");
    }
    // Data beyond the declared elements: a wrong count would silently drop what follows.
    if (reader.content_left()) {
        context.fail("more data than the header declares");
    }
    TriangleMesh mesh = builder.finish();
    if (attributes != nullptr) {
        store_extras(extras, *vertex_element, *attributes);
        texture.store(mesh, *attributes, context);
    }
    return mesh;
}

}  // namespace genflow::detail
