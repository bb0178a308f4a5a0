// SPDX-License-Identifier: MIT
#include "genflow/io/read_mesh.h"

#include <fstream>

#include "io/readers.h"

namespace genflow {

std::optional<MeshFormat> mesh_format_from_extension(const std::filesystem::path& path) {
    const std::string extension = path.extension().string();
    if (detail::iequals(extension, ".obj"))
        return MeshFormat::Obj;
    if (detail::iequals(extension, ".ply"))
        return MeshFormat::Ply;
    if (detail::iequals(extension, ".off"))
        return MeshFormat::Off;
    if (detail::iequals(extension, ".stl"))
        return MeshFormat::Stl;
    return std::nullopt;
}

TriangleMesh parse_mesh(std::string_view bytes, MeshFormat format, std::string_view source_name,
                        std::vector<std::string>* warnings) {
    const detail::ParseContext context{source_name, warnings};
    switch (format) {
        case MeshFormat::Obj:
            return detail::parse_obj(bytes, context);
        case MeshFormat::Ply:
            return detail::parse_ply(bytes, context);
        case MeshFormat::Off:
            return detail::parse_off(bytes, context);
        case MeshFormat::Stl:
            return detail::parse_stl(bytes, context);
    }
    context.fail("unknown mesh format");
}

TriangleMesh read_mesh(const std::filesystem::path& path, std::vector<std::string>* warnings) {
    const std::string name = path.string();
    const auto format = mesh_format_from_extension(path);
    if (!format) {
        throw IoError(name + ": unknown mesh format '" + path.extension().string() +
                      "' (expected .obj, .ply, .off or .stl)");
    }
    return parse_mesh(detail::read_mesh_file(path), *format, name, warnings);
}

namespace detail {

std::string read_mesh_file(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
        throw IoError(name + ": is a directory, not a mesh file");
    }
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        throw IoError(
            name + ": cannot open for reading (" +
            (std::filesystem::exists(path, error) ? "permission denied?" : "no such file") + ")");
    }
    file.seekg(0, std::ios::end);
    const std::streamoff size = file.tellg();
    file.seekg(0, std::ios::beg);
    if (size < 0) {
        throw IoError(name + ": cannot determine the file size");
    }
    std::string bytes(static_cast<std::size_t>(size), '\0');
    if (!file.read(bytes.data(), size)) {
        throw IoError(name + ": read error");
    }
    if (bytes.empty()) {
        throw IoError(name + ": empty file");
    }
    return bytes;
}

}  // namespace detail

}  // namespace genflow
