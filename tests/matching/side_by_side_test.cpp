// SPDX-License-Identifier: MIT
#include "matching/side_by_side.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
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
