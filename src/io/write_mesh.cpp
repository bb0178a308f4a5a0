// SPDX-License-Identifier: MIT
#include "genflow/io/write_mesh.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstring>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/io/atomic_file.h"
#include "genflow/io/mesh_format.h"
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

// Vertex colours as "v x y z r g b" (0–1), the extension MeshLab, Blender and trimesh read.
std::string encode_obj(const TriangleMesh& mesh, const VertexAttributes& attributes) {
    const bool colored = attributes.colors.rows() > 0;
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
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        out += "f";
        for (int c = 0; c < 3; ++c) {
            out += ' ';
            append_number(out, mesh.F(f, c) + 1);
        }
        out += '\n';
    }
    return out;
}

// Vertex colours as COFF: "x y z r g b a", 0–255.
std::string encode_off(const TriangleMesh& mesh, const VertexAttributes& attributes) {
    const bool colored = attributes.colors.rows() > 0;
    std::string out = colored ? "COFF\n" : "OFF\n";
    out += std::to_string(mesh.V.rows()) + " " + std::to_string(mesh.F.rows()) + " 0\n";
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            append_number(out, mesh.V(i, c));
            out += c < 2 || colored ? ' ' : '\n';
        }
        for (int c = 0; colored && c < 3; ++c) {
            append_number(out, static_cast<int>(attributes.colors(i, c)));
            out += ' ';
        }
        if (colored) {
            out += "255\n";
        }
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

// Vertex rows "x y z [scalars...] [red green blue]": scalars in the coordinates' type, colours
// as uchar, as MeshLab and CloudCompare write them.
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
    for (const auto& [name, values] : attributes.scalars) {
        out += "property " + type + " " + name + "\n";
    }
    for (const char* channel : {"red", "green", "blue"}) {
        out += colored ? std::string("property uchar ") + channel + "\n" : "";
    }
    out += "element face " + std::to_string(mesh.F.rows()) +
           "\nproperty list uchar int vertex_indices\nend_header\n";
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        const std::size_t row_start = out.size();
        for (int c = 0; c < 3; ++c) {
            append_value(out, mesh.V(i, c), binary, single);
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
            out += '\n';
        }
    }
    return out;
}

}  // namespace

namespace {

bool is_ply_name(const std::string& name) {
    return !name.empty() && std::none_of(name.begin(), name.end(), [](char c) {
        return static_cast<unsigned char>(c) <= ' ' || c == 0x7f;
    });
}

void check_attributes(const std::filesystem::path& path, const TriangleMesh& mesh,
                      const VertexAttributes& attributes) {
    if (attributes.colors.rows() != 0 && attributes.colors.rows() != mesh.V.rows()) {
        throw InvalidInput(path.string() + ": " + std::to_string(attributes.colors.rows()) +
                           " vertex colours for " + std::to_string(mesh.V.rows()) + " vertices");
    }
    for (const auto& [name, values] : attributes.scalars) {
        if (!is_ply_name(name) || name == "x" || name == "y" || name == "z" || name == "red" ||
            name == "green" || name == "blue") {
            throw InvalidInput(path.string() +
                               ": a vertex value needs a name of its own without "
                               "spaces, got \"" +
                               name + "\"");
        }
        if (values.size() != mesh.V.rows() || !detail::all_finite(values)) {
            throw InvalidInput(path.string() + ": vertex value " + name +
                               " needs a finite number per vertex");
        }
    }
}

}  // namespace

void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                const WriteMeshOptions& options) {
    write_mesh(path, mesh, VertexAttributes{}, options);
}

void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                const VertexAttributes& attributes, const WriteMeshOptions& options,
                std::vector<std::string>* warnings) {
    const auto format = mesh_format_from_extension(path);
    if (!format || *format == MeshFormat::Stl) {
        throw IoError(path.string() + ": cannot write format '" + path.extension().string() +
                      "' (expected .obj, .ply or .off)");
    }
    if (mesh.F.size() > 0 && (mesh.F.minCoeff() < 0 || mesh.F.maxCoeff() >= mesh.V.rows())) {
        throw InvalidInput("write_mesh: face indices must lie in [0, " +
                           std::to_string(mesh.V.rows()) + ")");
    }
    // The readers refuse such a file: what cannot be read back is not written.
    if (!detail::all_finite(mesh.V)) {
        throw InvalidInput(path.string() + ": the mesh to write has non-finite coordinates");
    }
    check_attributes(path, mesh, attributes);
    if (*format != MeshFormat::Ply && !attributes.scalars.empty() && warnings != nullptr) {
        warnings->push_back(path.string() + ": " + path.extension().string() +
                            " holds no vertex values (" + attributes.scalars.front().first +
                            (attributes.scalars.size() > 1 ? ", ..." : "") +
                            "); write .ply to keep them");
    }
    std::string bytes;
    switch (*format) {
        case MeshFormat::Obj:
            bytes = encode_obj(mesh, attributes);
            break;
        case MeshFormat::Off:
            bytes = encode_off(mesh, attributes);
            break;
        case MeshFormat::Ply:
        case MeshFormat::Stl:
            bytes = encode_ply(mesh, attributes, options);
            break;
    }
    write_file_atomically(path, bytes);
}

}  // namespace genflow
