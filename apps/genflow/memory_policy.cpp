// SPDX-License-Identifier: MIT
#include "memory_policy.h"

#include <unistd.h>

#include <array>
#include <cstdlib>
#include <fstream>

namespace genflow::cli {

namespace {

constexpr std::string_view kHugePages = "glibc.malloc.hugetlb";

// The path /proc/self/exe links to, empty if it cannot be read. The tool starts itself by it
// rather than by /proc/self/exe, whose name the process would take (`ps` and `pkill` would see
// "exe").
std::string own_executable() {
    std::array<char, 4096> path{};
    const ssize_t length = readlink("/proc/self/exe", path.data(), path.size() - 1);
    return length > 0 ? std::string(path.data(), static_cast<std::size_t>(length)) : "";
}

}  // namespace

void keep_freed_memory() {
#if defined(__GLIBC__)
    constexpr int kLargestHeapBlock = 32 << 20;  // glibc's DEFAULT_MMAP_THRESHOLD_MAX, 64-bit
    mallopt(M_MMAP_THRESHOLD, kLargestHeapBlock);
    mallopt(M_TRIM_THRESHOLD, 2 * kLargestHeapBlock);
#endif
}

std::optional<std::string> tunables_with_huge_pages(const char* current) {
    const std::string tunables = current != nullptr ? current : "";
    if (tunables.find(kHugePages) != std::string::npos) {
        return std::nullopt;
    }
    const std::string setting = std::string(kHugePages) + "=1";
    return tunables.empty() ? setting : tunables + ":" + setting;
}

bool huge_pages_on_request(std::string_view mode) {
    return mode.find("[madvise]") != std::string_view::npos;
}

void ask_for_huge_pages(char** argv) {
    ask_for_huge_pages(nullptr, argv);
}

void ask_for_huge_pages(const char* program, char** argv) {
#if GENFLOW_GLIBC_HAS_HUGE_PAGE_TUNABLE
    const char* current = std::getenv("GLIBC_TUNABLES");
    const std::optional<std::string> tunables = tunables_with_huge_pages(current);
    if (!tunables) {
        return;
    }
    std::ifstream mode_file("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string mode;
    if (!std::getline(mode_file, mode) || !huge_pages_on_request(mode)) {
        return;
    }
    const std::string executable = program != nullptr ? program : own_executable();
    if (executable.empty()) {
        return;
    }
    const std::optional<std::string> previous =
        current != nullptr ? std::optional<std::string>(current) : std::nullopt;
    setenv("GLIBC_TUNABLES", tunables->c_str(), 1);
    execv(executable.c_str(), argv);
    // Still here: the new start failed, and this process goes on as it was.
    if (previous) {
        setenv("GLIBC_TUNABLES", previous->c_str(), 1);
    } else {
        unsetenv("GLIBC_TUNABLES");
    }
#else
    (void)program;
    (void)argv;
#endif
}

}  // namespace genflow::cli
