// SPDX-License-Identifier: MIT
#include "genflow/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>

#include "genflow/exceptions.h"

namespace genflow {

namespace {

std::filesystem::path temporary_sibling(const std::filesystem::path& path) {
    static std::atomic<unsigned> counter{0};
    auto name = path.filename().string();
    name = "." + name + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    return path.parent_path() / name;
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
    const std::string name = path.string();
    if (path.filename().empty()) {
        throw IoError(name + ": not a file name");
    }
    const auto temporary = temporary_sibling(path);
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        throw IoError(name + ": cannot create file (" + std::strerror(errno) + ")");
    }
    const auto fail = [&](const std::string& what) {
        const std::string reason = std::strerror(errno);
        ::close(fd);
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw IoError(name + ": " + what + " (" + reason + ")");
    };
    std::size_t written = 0;
    while (written < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            fail("write failed");
        }
        written += static_cast<std::size_t>(n);
    }
    if (::fsync(fd) != 0) {
        fail("flush to disk failed");
    }
    if (::close(fd) != 0) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw IoError(name + ": close failed (" + std::strerror(errno) + ")");
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw IoError(name + ": cannot move the finished file into place (" + error.message() +
                      ")");
    }
}

}  // namespace genflow
