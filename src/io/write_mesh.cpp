// SPDX-License-Identifier: MIT
#include "genflow/io/write_mesh.h"

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

std::string encode_obj(const TriangleMesh& mesh) {
    std::string out = "# written by genflow\n";
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        out += "v";
        for (int c = 0; c < 3; ++c) {
            out += ' ';
            append_number(out, mesh.V(i, c));
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

std::string encode_off(const TriangleMesh& mesh) {
    std::string out = "OFF\n";
    out += std::to_string(mesh.V.rows()) + " " + std::to_string(mesh.F.rows()) + " 0\n";
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            append_number(out, mesh.V(i, c));
            out += c < 2 ? ' ' : '\n';
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

std::string encode_ply(const TriangleMesh& mesh, const WriteMeshOptions& options) {
    const bool binary = options.ply_encoding == PlyEncoding::BinaryLittleEndian;
    const bool single = options.ply_precision == PlyPrecision::Float;
    const char* type = single ? "float" : "double";
    std::string out = "ply\nformat ";
    out += binary ? "binary_little_endian" : "ascii";
    out +=
        " 1.0\ncomment written by genflow\nelement vertex " + std::to_string(mesh.V.rows()) + "\n";
    for (const char* axis : {"x", "y", "z"}) {
        out += std::string("property ") + type + " " + axis + "\n";
    }
    out += "element face " + std::to_string(mesh.F.rows()) +
           "\nproperty list uchar int vertex_indices\nend_header\n";
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const double value = mesh.V(i, c);
            if (binary) {
                single ? append_little_endian(out, static_cast<float>(value))
                       : append_little_endian(out, value);
            } else {
                single ? append_number(out, static_cast<double>(static_cast<float>(value)))
                       : append_number(out, value);
                out += c < 2 ? ' ' : '\n';
            }
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

void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                const WriteMeshOptions& options) {
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
    std::string bytes;
    switch (*format) {
        case MeshFormat::Obj:
            bytes = encode_obj(mesh);
            break;
        case MeshFormat::Off:
            bytes = encode_off(mesh);
            break;
        case MeshFormat::Ply:
        case MeshFormat::Stl:
            bytes = encode_ply(mesh, options);
            break;
    }
    write_file_atomically(path, bytes);
}

}  // namespace genflow
