// SPDX-License-Identifier: MIT
#include "memory_policy.h"

#include <unistd.h>

#include <array>
#include <cstdlib>
#include <fstream>

#if __has_include(<malloc.h>)
#include <malloc.h>  // defines __GLIBC__ where it is glibc's
#endif

// glibc.malloc.hugetlb is read from glibc 2.35 on.
#if defined(__GLIBC__)
#define GENFLOW_GLIBC_HAS_HUGE_PAGE_TUNABLE __GLIBC_PREREQ(2, 35)
#else
#define GENFLOW_GLIBC_HAS_HUGE_PAGE_TUNABLE 0
#endif

namespace genflow::cli {

namespace {

constexpr std::string_view kHugePages = "glibc.malloc.hugetlb";

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
    // The executable's own path rather than /proc/self/exe, whose name the process would take
    // (`ps` and `pkill` would see "exe").
    std::array<char, 4096> path{};
    const ssize_t length = readlink("/proc/self/exe", path.data(), path.size() - 1);
    if (length > 0) {
        ask_for_huge_pages(path.data(), argv);
    }
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
    const std::optional<std::string> previous =
        current != nullptr ? std::optional<std::string>(current) : std::nullopt;
    setenv("GLIBC_TUNABLES", tunables->c_str(), 1);
    execv(program, argv);
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
