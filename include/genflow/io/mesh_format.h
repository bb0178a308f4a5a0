// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <optional>

namespace genflow {

/// File formats genflow reads; all but STL can also be written.
enum class MeshFormat { Obj, Ply, Off, Stl };

/// The format named by the extension of `path` (case-insensitive: .obj, .ply, .off, .stl), or
/// nothing for any other extension.
[[nodiscard]] std::optional<MeshFormat> mesh_format_from_extension(
    const std::filesystem::path& path);

}  // namespace genflow
