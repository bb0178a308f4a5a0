// SPDX-License-Identifier: MIT
#include "genflow/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "genflow/exceptions.h"

namespace genflow {

namespace {

// The temporaries a signal must remove, in slots a signal handler can read: a fixed array of
// paths, each published by its flag. More unfinished writes at once than slots go untracked.
struct TrackedTemporary {
    std::atomic<bool> used{false};
    std::array<char, PATH_MAX> path{};
};
std::array<TrackedTemporary, 64> tracked;

int track(const std::filesystem::path& temporary) {
    const std::string& name = temporary.native();
    if (name.size() >= PATH_MAX) {
        return -1;
    }
    for (std::size_t slot = 0; slot < tracked.size(); ++slot) {
        bool expected = false;
        if (tracked[slot].used.compare_exchange_strong(expected, true)) {
            std::memcpy(tracked[slot].path.data(), name.c_str(), name.size() + 1);
            return static_cast<int>(slot);
        }
    }
    return -1;
}

void untrack(int slot) {
    if (slot >= 0) {
        tracked[static_cast<std::size_t>(slot)].path[0] = '\0';
        tracked[static_cast<std::size_t>(slot)].used.store(false);
    }
}

extern "C" void remove_tracked_and_reraise(int signal) {
    for (TrackedTemporary& temporary : tracked) {
        if (temporary.used.load() && temporary.path[0] != '\0') {
            ::unlink(temporary.path.data());
        }
    }
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

// A finished temporary waiting for its transaction's commit().
struct Pending {
    std::filesystem::path temporary;
    std::filesystem::path path;
    int slot = -1;
};

std::mutex transaction_mutex;
bool transaction_open = false;
std::vector<Pending> pending;

void discard(const Pending& file) {
    std::error_code ignored;
    std::filesystem::remove(file.temporary, ignored);
    untrack(file.slot);
}

std::filesystem::path temporary_sibling(const std::filesystem::path& path) {
    static std::atomic<unsigned> counter{0};
    auto name = path.filename().string();
    name = "." + name + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    return path.parent_path() / name;
}

// The file a write to `path` replaces: the one a chain of symbolic links ends at, so that the
// links stay (even when that file is yet to be written); else `path` itself. The chain is
// followed as the kernel follows it, up to its limit of 40 links.
std::filesystem::path written_through(const std::filesystem::path& path) {
    std::filesystem::path current = path;
    std::error_code error;
    for (int link = 0; std::filesystem::is_symlink(current, error); ++link) {
        const std::filesystem::path target = std::filesystem::read_symlink(current, error);
        if (error || link == 40) {
            throw OutputError(path.string() + ": a symbolic link that cannot be followed");
        }
        current = target.is_absolute() ? target : current.parent_path() / target;
    }
    return current;
}

// Moves a finished temporary into place.
void rename_into_place(const Pending& file, const std::string& name) {
    std::error_code error;
    std::filesystem::rename(file.temporary, file.path, error);
    if (error) {
        discard(file);
        throw OutputError(name + ": cannot move the finished file into place (" + error.message() +
                          ")");
    }
    untrack(file.slot);
}

// Writes all of `bytes` to `fd`, flushed to disk; false with errno set on failure.
bool write_all(int fd, std::string_view bytes, const char*& failed) {
    std::size_t written = 0;
    while (written < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            failed = "write failed";
            return false;
        }
        written += static_cast<std::size_t>(n);
    }
    if (::fsync(fd) != 0) {
        failed = "flush to disk failed";
        return false;
    }
    return true;
}

}  // namespace

void check_output_path(const std::filesystem::path& path) {
    const std::string name = path.string();
    if (path.filename().empty()) {
        throw OutputError(name + ": not a file name");
    }
    const std::filesystem::path target = written_through(path);
    std::error_code error;
    if (std::filesystem::is_directory(target, error)) {
        throw OutputError(name + ": is a directory");
    }
    const std::filesystem::path directory =
        target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
    if (!std::filesystem::is_directory(directory, error)) {
        throw OutputError(name + ": cannot be written: the directory " + directory.string() +
                          " does not exist");
    }
    if (::access(directory.c_str(), W_OK | X_OK) != 0) {
        throw OutputError(name + ": cannot be written: the directory " + directory.string() +
                          " is not writable");
    }
}

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
    const std::string name = path.string();
    if (path.filename().empty()) {
        throw OutputError(name + ": not a file name");
    }
    const std::filesystem::path target = written_through(path);
    Pending file{temporary_sibling(target), target};
    file.slot = track(file.temporary);
    const int fd = ::open(file.temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        const std::string reason = std::strerror(errno);
        untrack(file.slot);
        throw OutputError(name + ": cannot create file (" + reason + ")");
    }
    // An existing output keeps its permissions (a 0600 file stays private).
    struct stat existing {};
    if (::stat(file.path.c_str(), &existing) == 0 && S_ISREG(existing.st_mode)) {
        (void)::fchmod(fd, existing.st_mode & 07777);
    }
    const char* failed = nullptr;
    if (!write_all(fd, bytes, failed) || ::close(fd) != 0) {
        const std::string reason = std::strerror(errno);
        if (failed != nullptr) {
            ::close(fd);
        }
        discard(file);
        throw OutputError(name + ": " + (failed != nullptr ? failed : "close failed") + " (" +
                          reason + ")");
    }
    {
        const std::lock_guard lock(transaction_mutex);
        if (transaction_open) {
            pending.push_back(std::move(file));
            return;
        }
    }
    rename_into_place(file, name);
}

OutputTransaction::OutputTransaction() {
    const std::lock_guard lock(transaction_mutex);
    outermost_ = !transaction_open;
    transaction_open = true;
}

OutputTransaction::~OutputTransaction() {
    if (!outermost_) {
        return;
    }
    const std::lock_guard lock(transaction_mutex);
    for (const Pending& file : pending) {
        discard(file);
    }
    pending.clear();
    transaction_open = false;
}

void OutputTransaction::commit() {
    if (!outermost_) {
        return;
    }
    const std::lock_guard lock(transaction_mutex);
    std::vector<Pending> files;
    files.swap(pending);
    for (std::size_t k = 0; k < files.size(); ++k) {
        try {
            rename_into_place(files[k], files[k].path.string());
        } catch (const OutputError&) {
            for (std::size_t rest = k + 1; rest < files.size(); ++rest) {
                discard(files[rest]);
            }
            throw;
        }
    }
    transaction_open = false;
}

void remove_temporaries_on_signals() {
    for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
        std::signal(signal, remove_tracked_and_reraise);
    }
}

}  // namespace genflow
