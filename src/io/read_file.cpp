// SPDX-License-Identifier: MIT
#include "genflow/io/read_file.h"

#include <fstream>
#include <iterator>

#include "genflow/exceptions.h"

namespace genflow {

std::string read_file(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code error;
    const std::filesystem::file_status status = std::filesystem::status(path, error);
    if (!std::filesystem::exists(status)) {
        throw IoError(name + ": cannot open for reading (no such file)");
    }
    if (std::filesystem::is_directory(status)) {
        throw IoError(name + ": is a directory, not a file");
    }
    if (!std::filesystem::is_regular_file(status)) {
        throw IoError(name + ": not a regular file (a pipe, socket or device is not read)");
    }
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        throw IoError(name + ": cannot open for reading (permission denied?)");
    }
    std::string bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
    if (file.bad()) {
        throw IoError(name + ": read error");
    }
    return bytes;
}

}  // namespace genflow
