// SPDX-License-Identifier: MIT
// How the tool's process takes and keeps memory. A command allocates and frees the same large
// arrays again and again (a mesh's copies, its checks' buckets, a factor's workspace); glibc's
// malloc gives blocks above 128 KiB back to the kernel when they are freed, so every new one is
// faulted in page by page again; and each 4 KiB page is a fault of its own.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#if __has_include(<malloc.h>)
#include <malloc.h>  // defines __GLIBC__ where it is glibc's
#endif

// Whether glibc reads glibc.malloc.hugetlb, which it does from 2.35 on.
#if defined(__GLIBC__)
#define GENFLOW_GLIBC_HAS_HUGE_PAGE_TUNABLE __GLIBC_PREREQ(2, 35)
#else
#define GENFLOW_GLIBC_HAS_HUGE_PAGE_TUNABLE 0
#endif

namespace genflow::cli {

/// Starts glibc's malloc where its own adaptive thresholds end: blocks up to 32 MiB come from the
/// heap and are reused, and the heap keeps up to 64 MiB of freed memory at its top (glibc's
/// ceiling for its mmap threshold and its rule of a trim threshold twice that). On a 2-core
/// virtual machine, `smooth --steps 0` on the 43K armadillo took 0.077 instead of 0.110 s, at
/// the same peak memory (docs/benchmarks.md, "Dear system calls"). Nothing where malloc is not
/// glibc's.
void keep_freed_memory();

/// Runs the tool again, once, from its start, with glibc's malloc asked to back its memory with
/// transparent huge pages (GLIBC_TUNABLES gains glibc.malloc.hugetlb=1, which glibc reads only
/// when a process starts), where the kernel gives them only to memory that asks ("madvise"
/// mode): one fault then maps 2 MiB where it mapped 4 KiB. On a 2-core virtual machine,
/// `smooth --steps 0` on the 48K horse took 0.055 instead of 0.087 s (docs/benchmarks.md, "Dear
/// system calls"). Returns, having changed nothing, where GLIBC_TUNABLES already names the
/// setting (the user's choice, or this process after its new start), where the kernel gives
/// huge pages always or never, where malloc is not glibc's 2.35 or later, or where the new start
/// fails. Must be called before anything else in `main`.
void ask_for_huge_pages(char** argv);

/// ask_for_huge_pages() starting `program`; null, the tool itself, by the path /proc/self/exe
/// links to (found only when it starts again).
void ask_for_huge_pages(const char* program, char** argv);

/// GLIBC_TUNABLES with glibc.malloc.hugetlb=1 added to `current` (null when it is unset);
/// nullopt when `current` already names glibc.malloc.hugetlb.
[[nodiscard]] std::optional<std::string> tunables_with_huge_pages(const char* current);

/// Whether the kernel's mode of transparent huge pages (the text of
/// /sys/kernel/mm/transparent_hugepage/enabled, the chosen mode in brackets) gives them only to
/// memory that asks.
[[nodiscard]] bool huge_pages_on_request(std::string_view mode);

}  // namespace genflow::cli
