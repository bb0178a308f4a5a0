// SPDX-License-Identifier: MIT
#include "genflow/io/write_mesh.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/io/atomic_file.h"
#include "genflow/io/mesh_format.h"
#include "io/attribute_checks.h"
#include "io/glb_writer.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

// Shortest decimal text that parses back to the same double.
void append_number(std::string& out, double value) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    out.append(buffer, result.ptr);
}

void append_number(std::string& out, int value) {
    char buffer[16];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    out.append(buffer, result.ptr);
}

template <typename T>
void append_little_endian(std::string& out, T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) {
        std::reverse(raw, raw + sizeof(T));
    }
    out.append(raw, sizeof(T));
}

// A colour's channel as OBJ's vertex colours and PLY's float colours give it: 0–1.
double unit_channel(std::uint8_t value) {
    return value / 255.0;
}

// Texture coordinates as an OBJ file gives them: `vt` rows, and per face the rows of its
// corners (0-based); per corner where the attributes have them so, else one row per vertex.
struct ObjTexture {
    const Eigen::MatrixX2d* rows = nullptr;
    const Eigen::MatrixX3i* corners = nullptr;  // null: row i for vertex i
};

ObjTexture obj_texture(const VertexAttributes& attributes) {
    if (attributes.corner_uv_faces.rows() > 0) {
        return {&attributes.corner_uvs, &attributes.corner_uv_faces};
    }
    return {attributes.uvs.rows() > 0 ? &attributes.uvs : nullptr, nullptr};
}

// Vertex colours as "v x y z r g b" (0–1), the extension MeshLab, Blender and trimesh read;
// texture coordinates as `vt` records named by the faces' corners ("f v/t").
std::string encode_obj(const TriangleMesh& mesh, const VertexAttributes& attributes) {
    const bool colored = attributes.colors.rows() > 0;
    const ObjTexture texture = obj_texture(attributes);
    std::string out = "# written by genflow\n";
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        out += "v";
        for (int c = 0; c < 3; ++c) {
            out += ' ';
            append_number(out, mesh.V(i, c));
        }
        for (int c = 0; colored && c < 3; ++c) {
            out += ' ';
            append_number(out, unit_channel(attributes.colors(i, c)));
        }
        out += '\n';
    }
    for (Eigen::Index t = 0; texture.rows != nullptr && t < texture.rows->rows(); ++t) {
        out += "vt ";
        append_number(out, (*texture.rows)(t, 0));
        out += ' ';
        append_number(out, (*texture.rows)(t, 1));
        out += '\n';
    }
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        out += "f";
        for (int c = 0; c < 3; ++c) {
            out += ' ';
            append_number(out, mesh.F(f, c) + 1);
            if (texture.rows != nullptr) {
                out += '/';
                append_number(
                    out,
                    (texture.corners != nullptr ? (*texture.corners)(f, c) : mesh.F(f, c)) + 1);
            }
        }
        out += '\n';
    }
    return out;
}

// Geomview's OFF with the columns the attributes have, announced by the keyword's prefixes:
// "[ST][C][N]OFF", vertex lines "x y z [nx ny nz] [r g b a] [s t]" (colours 0–255).
std::string encode_off(const TriangleMesh& mesh, const VertexAttributes& attributes) {
    const bool normals = attributes.normals.rows() > 0;
    const bool colored = attributes.colors.rows() > 0;
    const bool textured = attributes.uvs.rows() > 0;
    std::string out =
        std::string(textured ? "ST" : "") + (colored ? "C" : "") + (normals ? "N" : "") + "OFF\n";
    out += std::to_string(mesh.V.rows()) + " " + std::to_string(mesh.F.rows()) + " 0\n";
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            append_number(out, mesh.V(i, c));
            out += ' ';
        }
        for (int c = 0; normals && c < 3; ++c) {
            append_number(out, attributes.normals(i, c));
            out += ' ';
        }
        for (int c = 0; colored && c < 3; ++c) {
            append_number(out, static_cast<int>(attributes.colors(i, c)));
            out += ' ';
        }
        out += colored ? "255 " : "";
        for (int c = 0; textured && c < 2; ++c) {
            append_number(out, attributes.uvs(i, c));
            out += ' ';
        }
        out.back() = '\n';
    }
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        out += "3";
        for (int c = 0; c < 3; ++c) {
            out += ' ';
            append_number(out, mesh.F(f, c));
        }
        out += '\n';
    }
    return out;
}

// One number of a vertex's row, as the header declares it.
void append_value(std::string& out, double value, bool binary, bool single) {
    if (binary) {
        single ? append_little_endian(out, static_cast<float>(value))
               : append_little_endian(out, value);
    } else {
        out += ' ';
        single ? append_number(out, static_cast<double>(static_cast<float>(value)))
               : append_number(out, value);
    }
}

// Face f's `texcoord` list: 6, then u, v of each corner, as floats.
void append_corner_uvs(std::string& out, const VertexAttributes& attributes, Eigen::Index f,
                       bool binary) {
    if (binary) {
        out += static_cast<char>(6);
    } else {
        out += " 6";
    }
    for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < 2; ++k) {
            append_value(out, attributes.corner_uvs(attributes.corner_uv_faces(f, c), k), binary,
                         true);
        }
    }
}

// Vertex rows "x y z [nx ny nz] [texture_u texture_v] [values...] [red green blue]": normals,
// texture coordinates and values in the coordinates' type, colours as uchar; per-corner texture
// coordinates as the faces' `texcoord` lists (u, v per corner): as MeshLab writes them.
std::string encode_ply(const TriangleMesh& mesh, const VertexAttributes& attributes,
                       const WriteMeshOptions& options) {
    const bool binary = options.ply_encoding == PlyEncoding::BinaryLittleEndian;
    const bool single = options.ply_precision == PlyPrecision::Float;
    const bool colored = attributes.colors.rows() > 0;
    const std::string type = single ? "float" : "double";
    std::string out = "ply\nformat ";
    out += binary ? "binary_little_endian" : "ascii";
    out +=
        " 1.0\ncomment written by genflow\nelement vertex " + std::to_string(mesh.V.rows()) + "\n";
    for (const char* axis : {"x", "y", "z"}) {
        out += "property " + type + " " + axis + "\n";
    }
    const bool with_normals = attributes.normals.rows() > 0;
    for (const char* axis : {"nx", "ny", "nz"}) {
        out += with_normals ? "property " + type + " " + axis + "\n" : "";
    }
    const bool with_uvs = attributes.uvs.rows() > 0;
    for (const char* coordinate : {"texture_u", "texture_v"}) {
        out += with_uvs ? "property " + type + " " + coordinate + "\n" : "";
    }
    for (const auto& [name, values] : attributes.scalars) {
        out += "property " + type + " " + name + "\n";
    }
    for (const char* channel : {"red", "green", "blue"}) {
        out += colored ? std::string("property uchar ") + channel + "\n" : "";
    }
    const bool with_corner_uvs = attributes.corner_uv_faces.rows() > 0;
    out += "element face " + std::to_string(mesh.F.rows()) +
           "\nproperty list uchar int vertex_indices\n" +
           (with_corner_uvs ? "property list uchar float texcoord\n" : "") + "end_header\n";
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        const std::size_t row_start = out.size();
        for (int c = 0; c < 3; ++c) {
            append_value(out, mesh.V(i, c), binary, single);
        }
        for (int c = 0; with_normals && c < 3; ++c) {
            append_value(out, attributes.normals(i, c), binary, single);
        }
        for (int c = 0; with_uvs && c < 2; ++c) {
            append_value(out, attributes.uvs(i, c), binary, single);
        }
        for (const auto& scalar : attributes.scalars) {
            append_value(out, scalar.second[i], binary, single);
        }
        for (int c = 0; colored && c < 3; ++c) {
            if (binary) {
                out += static_cast<char>(attributes.colors(i, c));
            } else {
                out += ' ';
                append_number(out, static_cast<int>(attributes.colors(i, c)));
            }
        }
        if (!binary) {
            out.erase(row_start, 1);  // the row's leading space
            out += '\n';
        }
    }
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        if (binary) {
            out += static_cast<char>(3);
            for (int c = 0; c < 3; ++c) {
                append_little_endian(out, static_cast<std::int32_t>(mesh.F(f, c)));
            }
        } else {
            out += "3";
            for (int c = 0; c < 3; ++c) {
                out += ' ';
                append_number(out, mesh.F(f, c));
            }
        }
        if (with_corner_uvs) {
            append_corner_uvs(out, attributes, f, binary);
        }
        if (!binary) {
            out += '\n';
        }
    }
    return out;
}

// Binary STL: an 80-byte header, the count, and per face its unit normal and corners as floats.
std::string encode_stl(const TriangleMesh& mesh) {
    std::string out = "binary STL written by genflow";
    out.resize(80, ' ');
    append_little_endian(out, static_cast<std::uint32_t>(mesh.F.rows()));
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)).transpose();
        const Eigen::Vector3d b = mesh.V.row(mesh.F(f, 1)).transpose();
        const Eigen::Vector3d c = mesh.V.row(mesh.F(f, 2)).transpose();
        const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();  // 0 if degenerate
        for (const Eigen::Vector3d& point : {normal, a, b, c}) {
            for (int k = 0; k < 3; ++k) {
                append_little_endian(out,
                                     std::isfinite(point[k]) ? static_cast<float>(point[k]) : 0.0F);
            }
        }
        append_little_endian(out, std::uint16_t{0});
    }
    return out;
}

// The formats write_mesh() writes, by extension.
enum class Written { Obj, Ply, Off, Stl, Glb };

std::optional<Written> written_format(const std::filesystem::path& path) {
    if (const auto format = mesh_format_from_extension(path)) {
        switch (*format) {
            case MeshFormat::Obj:
                return Written::Obj;
            case MeshFormat::Ply:
                return Written::Ply;
            case MeshFormat::Off:
                return Written::Off;
            case MeshFormat::Stl:
                return Written::Stl;
        }
    }
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension == ".glb" ? std::optional(Written::Glb) : std::nullopt;
}

// What `format` leaves out of `attributes`, as a warning's words; empty if nothing. glTF gets
// normals of its own, computed from the faces.
std::string left_out(Written format, const VertexAttributes& attributes) {
    std::vector<const char*> missing;
    if (format == Written::Stl && attributes.colors.rows() > 0) {
        missing.push_back("colours");
    }
    if (format != Written::Ply && format != Written::Off && attributes.normals.rows() > 0) {
        missing.push_back("normals");
    }
    if (format != Written::Ply && format != Written::Glb && !attributes.scalars.empty()) {
        missing.push_back("values");
    }
    const bool texture = format == Written::Obj || format == Written::Ply;
    if (!texture && format != Written::Glb && format != Written::Off && attributes.uvs.rows() > 0) {
        missing.push_back("texture coordinates");
    }
    if (!texture && attributes.corner_uv_faces.rows() > 0) {
        missing.push_back("texture coordinates per corner");
    }
    if (format == Written::Obj && attributes.uvs.rows() > 0 &&
        attributes.corner_uv_faces.rows() > 0) {
        missing.push_back("texture coordinates per vertex beside those per corner");
    }
    std::string words;
    for (std::size_t k = 0; k < missing.size(); ++k) {
        words += (k == 0 ? "vertex " : k + 1 == missing.size() ? " and " : ", ");
        words += missing[k];
    }
    return words;
}

}  // namespace

void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                const WriteMeshOptions& options) {
    write_mesh(path, mesh, VertexAttributes{}, options);
}

bool is_writable_mesh_path(const std::filesystem::path& path) {
    return written_format(path).has_value();
}

void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                const VertexAttributes& attributes, const WriteMeshOptions& options,
                std::vector<std::string>* warnings) {
    const auto format = written_format(path);
    if (!format) {
        throw IoError(path.string() + ": cannot write format '" + path.extension().string() +
                      "' (expected .obj, .ply, .off, .stl or .glb)");
    }
    detail::check_face_indices("write_mesh", mesh.F, mesh.V.rows());
    // The readers refuse such a file: what cannot be read back is not written.
    if (!detail::all_finite(mesh.V)) {
        throw InvalidInput(path.string() + ": the mesh to write has non-finite coordinates");
    }
    detail::check_attributes(path, mesh, attributes);
    if (const std::string missing = left_out(*format, attributes);
        !missing.empty() && warnings != nullptr) {
        warnings->push_back(path.string() + ": " + path.extension().string() + " holds no " +
                            missing + "; write .ply to keep them");
    }
    std::string bytes;
    switch (*format) {
        case Written::Obj:
            bytes = encode_obj(mesh, attributes);
            break;
        case Written::Off:
            bytes = encode_off(mesh, attributes);
            break;
        case Written::Ply:
            bytes = encode_ply(mesh, attributes, options);
            break;
        case Written::Stl:
            bytes = encode_stl(mesh);
            break;
        case Written::Glb:
            bytes = detail::encode_glb(mesh, attributes);
            break;
    }
    write_file_atomically(path, bytes);
}

}  // namespace genflow
