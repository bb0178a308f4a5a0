// SPDX-License-Identifier: MIT
#include "genflow/io/read_mesh.h"

#include "genflow/io/read_file.h"
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
                        std::vector<std::string>* warnings, VertexAttributes* attributes) {
    const detail::ParseContext context{source_name, warnings};
    if (attributes != nullptr) {
        *attributes = {};
    }
    switch (format) {
        case MeshFormat::Obj:
            return detail::parse_obj(bytes, context, attributes);
        case MeshFormat::Ply:
            return detail::parse_ply(bytes, context, attributes);
        case MeshFormat::Off:
            return detail::parse_off(bytes, context, attributes);
        case MeshFormat::Stl:
            return detail::parse_stl(bytes, context);
    }
    context.fail("unknown mesh format");
}

TriangleMesh read_mesh(const std::filesystem::path& path, std::vector<std::string>* warnings,
                       VertexAttributes* attributes) {
    const std::string name = path.string();
    const auto format = mesh_format_from_extension(path);
    if (!format) {
        throw IoError(name + ": unknown mesh format '" + path.extension().string() +
                      "' (expected .obj, .ply, .off or .stl)");
    }
    return parse_mesh(detail::read_mesh_file(path), *format, name, warnings, attributes);
}

namespace detail {

std::string read_mesh_file(const std::filesystem::path& path) {
    std::string bytes = read_file(path);
    if (bytes.empty()) {
        throw IoError(path.string() + ": empty file");
    }
    return bytes;
}

}  // namespace detail

}  // namespace genflow
