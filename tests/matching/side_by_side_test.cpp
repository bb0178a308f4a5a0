// SPDX-License-Identifier: MIT
#include "matching/side_by_side.h"

#include <gtest/gtest.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <array>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace genflow {
namespace {

// Three contenders on two threads, each running its stiffness candidates side by side in
// turn, as a match does: every inner task runs once, and each outer task sees all of its own
// inner tasks done when its call returns.
TEST(RunSideBySide, RunsEveryNestedTaskOnce) {
    constexpr std::size_t kOuter = 3;
    constexpr std::size_t kInner = 4;
    std::vector<std::atomic<int>> runs(kOuter * kInner);
    std::vector<int> seen_done(kOuter, 0);
    detail::run_side_by_side(kOuter, [&](std::size_t k) {
        detail::run_side_by_side(kInner, [&](std::size_t t) { ++runs[k * kInner + t]; });
        for (std::size_t t = 0; t < kInner; ++t) {
            seen_done[k] += runs[k * kInner + t].load();
        }
    });
    for (const std::atomic<int>& count : runs) {
        EXPECT_EQ(count.load(), 1);
    }
    for (const int done : seen_done) {
        EXPECT_EQ(done, static_cast<int>(kInner));
    }
}

// One start ends at once, the other runs two candidates side by side: the thread that ran the
// short one must take a candidate rather than wait for the other start to end. Each candidate
// waits (10 s at most) for the other to start, so both run at once only on two threads.
TEST(RunSideBySide, AFreeThreadRunsTheNestedTasksOfABusySibling) {
#ifdef _OPENMP
    if (omp_get_max_threads() < 2) {
        GTEST_SKIP() << "needs two OpenMP threads";
    }
    for (const std::size_t busy : {0, 1}) {
        for (int repeat = 0; repeat < 5; ++repeat) {
            std::atomic<int> started = 0;
            std::array<int, 2> thread{-1, -1};
            detail::run_side_by_side(2, [&](std::size_t k) {
                if (k != busy) {
                    return;
                }
                detail::run_side_by_side(2, [&](std::size_t t) {
                    thread[t] = omp_get_thread_num();
                    ++started;
                    const auto deadline =
                        std::chrono::steady_clock::now() + std::chrono::seconds(10);
                    while (started.load() < 2 && std::chrono::steady_clock::now() < deadline) {
                        std::this_thread::yield();
                    }
                });
            });
            EXPECT_NE(thread[0], thread[1]) << "busy start " << busy << ", repeat " << repeat;
        }
    }
#else
    GTEST_SKIP() << "built without OpenMP";
#endif
}

TEST(RunSideBySide, RethrowsATasksExceptionOnceAllHaveEnded) {
    std::atomic<int> finished = 0;
    EXPECT_THROW(detail::run_side_by_side(5,
                                          [&](std::size_t k) {
                                              if (k == 2) {
                                                  throw std::runtime_error("task 2 failed");
                                              }
                                              ++finished;
                                          }),
                 std::runtime_error);
    EXPECT_EQ(finished.load(), 4);
    // One task, and none.
    int single = 0;
    detail::run_side_by_side(1, [&](std::size_t k) { single += static_cast<int>(k) + 1; });
    EXPECT_EQ(single, 1);
    detail::run_side_by_side(0, [&](std::size_t) { ++single; });
    EXPECT_EQ(single, 1);
}

}  // namespace
}  // namespace genflow
