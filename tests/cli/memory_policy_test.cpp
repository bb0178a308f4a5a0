// SPDX-License-Identifier: MIT
// The tool's memory policy: after keep_freed_memory(), a large block comes from malloc's heap and
// stays there when freed, instead of being mapped for itself and given back to the kernel; and
// ask_for_huge_pages() starts the program again with glibc's huge-page setting where the kernel
// gives huge pages on request, and leaves a setting of the user's alone.
#include "memory_policy.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

#if __has_include(<malloc.h>)
#include <malloc.h>
#endif

namespace genflow {
namespace {

TEST(MemoryPolicy, KeepsAFreedLargeBlockInTheHeap) {
#if !defined(__GLIBC__) || defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "glibc's own malloc only (a sanitizer replaces it)";
#else
    constexpr std::size_t kBlock = std::size_t{24} << 20;  // above malloc's default thresholds
    cli::keep_freed_memory();
    const struct mallinfo2 before = mallinfo2();
    void* block = std::malloc(kBlock);
    ASSERT_NE(block, nullptr);
    static_cast<volatile char*>(block)[kBlock - 1] = 1;
    const struct mallinfo2 held = mallinfo2();
    EXPECT_EQ(held.hblkhd, before.hblkhd);  // not a mapping of its own
    std::free(block);
    const struct mallinfo2 after = mallinfo2();
    EXPECT_EQ(after.arena, held.arena);  // the heap was not trimmed
    EXPECT_GE(after.fordblks, kBlock);
#endif
}

TEST(MemoryPolicy, AddsTheHugePageSettingToTheTunablesUnlessOneIsNamed) {
    EXPECT_EQ(cli::tunables_with_huge_pages(nullptr), "glibc.malloc.hugetlb=1");
    EXPECT_EQ(cli::tunables_with_huge_pages(""), "glibc.malloc.hugetlb=1");
    EXPECT_EQ(cli::tunables_with_huge_pages("glibc.malloc.arena_max=2"),
              "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
    EXPECT_EQ(cli::tunables_with_huge_pages("glibc.malloc.hugetlb=0"), std::nullopt);
    EXPECT_EQ(cli::tunables_with_huge_pages("glibc.malloc.arena_max=2:glibc.malloc.hugetlb=2"),
              std::nullopt);
}

TEST(MemoryPolicy, ReadsTheKernelsHugePageMode) {
    EXPECT_TRUE(cli::huge_pages_on_request("always [madvise] never"));
    EXPECT_FALSE(cli::huge_pages_on_request("[always] madvise never"));
    EXPECT_FALSE(cli::huge_pages_on_request("always madvise [never]"));
    EXPECT_FALSE(cli::huge_pages_on_request(""));
}

// What a child that calls ask_for_huge_pages("/usr/bin/env", {"env"}) with GLIBC_TUNABLES set to
// `tunables` (null: unset) printed, and its exit code: env's 0 if it was started, else 3.
struct ChildRun {
    std::string output;
    int exit_code = -1;
};

ChildRun run_child_asking_for_huge_pages(const char* tunables) {
    int pipe_ends[2];
    if (pipe(pipe_ends) != 0) {
        return {};
    }
    const pid_t child = fork();
    if (child == 0) {
        dup2(pipe_ends[1], STDOUT_FILENO);
        close(pipe_ends[0]);
        if (tunables != nullptr) {
            setenv("GLIBC_TUNABLES", tunables, 1);
        } else {
            unsetenv("GLIBC_TUNABLES");
        }
        char program_name[] = "env";
        char* argv[] = {program_name, nullptr};
        cli::ask_for_huge_pages("/usr/bin/env", argv);
        _exit(3);
    }
    close(pipe_ends[1]);
    ChildRun run;
    char buffer[4096];
    for (ssize_t got = 0; (got = read(pipe_ends[0], buffer, sizeof buffer)) > 0;) {
        run.output.append(buffer, static_cast<std::size_t>(got));
    }
    close(pipe_ends[0]);
    int status = 0;
    if (waitpid(child, &status, 0) == child && WIFEXITED(status)) {
        run.exit_code = WEXITSTATUS(status);
    }
    return run;
}

TEST(MemoryPolicy, StartsAgainWithHugePagesWhereTheKernelGivesThemOnRequest) {
#if !GENFLOW_GLIBC_HAS_HUGE_PAGE_TUNABLE
    GTEST_SKIP() << "glibc 2.35 or later only (the setting is glibc's)";
#else
    std::ifstream mode_file("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string mode;
    std::getline(mode_file, mode);
    const ChildRun run = run_child_asking_for_huge_pages(nullptr);
    if (cli::huge_pages_on_request(mode)) {
        EXPECT_EQ(run.exit_code, 0);
        EXPECT_NE(run.output.find("GLIBC_TUNABLES=glibc.malloc.hugetlb=1\n"), std::string::npos)
            << run.output;
    } else {
        EXPECT_EQ(run.exit_code, 3) << "started again where the kernel's mode is " << mode;
    }
    const ChildRun users = run_child_asking_for_huge_pages("glibc.malloc.hugetlb=0");
    EXPECT_EQ(users.exit_code, 3) << "started again over the user's setting";
#endif
}

}  // namespace
}  // namespace genflow
