// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <string>

namespace genflow {

/// The whole of a regular file, as bytes. Only a regular file is opened (or a link to one): a
/// named pipe would block until something writes into it, and a device may never end.
/// \throws IoError "<path>: <problem>" if it does not exist, is a directory, a pipe, a socket
///         or a device, cannot be opened or read.
[[nodiscard]] std::string read_file(const std::filesystem::path& path);

}  // namespace genflow
