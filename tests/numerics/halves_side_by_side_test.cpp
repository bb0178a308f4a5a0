// SPDX-License-Identifier: MIT
// Two halves run side by side on threads of their own: each on its own thread, the OpenMP
// regions it opens one thread wide, and a failure of either half reaches the caller.
#include "numerics/halves_side_by_side.h"

#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <thread>

namespace genflow {
namespace {

#ifdef _OPENMP

// The thread each half ran on, how many parallel regions enclosed it (a region opened inside
// one costs about twice one opened outside any), and how many threads a region it opened (as
// CHOLMOD's supernodal factorization does, asking for four) had.
struct HalfRecord {
    std::thread::id thread;
    int enclosing_regions = -1;
    int region_threads = 0;
};

std::array<HalfRecord, 2> record_halves() {
    std::array<HalfRecord, 2> records;
    detail::for_both_halves_on_own_threads([&](int h) {
        HalfRecord& record = records[static_cast<std::size_t>(h)];
        record.thread = std::this_thread::get_id();
        record.enclosing_regions = omp_get_level();
#pragma omp parallel num_threads(4)
        {
#pragma omp master
            record.region_threads = omp_get_num_threads();
        }
    });
    return records;
}

TEST(HalvesSideBySide, RunOnTwoThreadsOfTheirOwnWhoseRegionsAreOneThreadWide) {
    if (omp_get_max_threads() < 2) {
        GTEST_SKIP() << "one thread: the halves run one after the other";
    }
    const std::array<HalfRecord, 2> records = record_halves();
    EXPECT_EQ(records[0].thread, std::this_thread::get_id());
    EXPECT_NE(records[1].thread, records[0].thread);
    EXPECT_EQ(records[0].enclosing_regions, 0);
    EXPECT_EQ(records[1].enclosing_regions, 0);
    EXPECT_EQ(records[0].region_threads, 1);
    EXPECT_EQ(records[1].region_threads, 1);
}

TEST(HalvesSideBySide, RunOneAfterTheOtherOnTheCallersThreadInsideAParallelRegion) {
    std::array<HalfRecord, 2> records;
    std::thread::id caller;
#pragma omp parallel num_threads(2)
    {
#pragma omp single
        {
            caller = std::this_thread::get_id();
            records = record_halves();
        }
    }
    EXPECT_EQ(records[0].thread, caller);
    EXPECT_EQ(records[1].thread, caller);
    EXPECT_EQ(records[0].region_threads, 1);
    EXPECT_EQ(records[1].region_threads, 1);
}

TEST(HalvesSideBySide, CarryAFailureOfEitherHalfToTheCaller) {
    if (omp_get_max_threads() < 2) {
        GTEST_SKIP() << "one thread: the halves run as for_both_halves() runs them";
    }
    for (const int failing : {0, 1}) {
        std::array<bool, 2> ran{false, false};
        EXPECT_THROW(detail::for_both_halves_on_own_threads([&](int h) {
                         ran[static_cast<std::size_t>(h)] = true;
                         if (h == failing) {
                             throw std::runtime_error("half failed");
                         }
                     }),
                     std::runtime_error)
            << "half " << failing;
        EXPECT_TRUE(ran[0] && ran[1]) << "half " << failing;
    }
}

#endif

}  // namespace
}  // namespace genflow
