// SPDX-License-Identifier: MIT
// The tool's memory policy: after keep_freed_memory(), a large block comes from malloc's heap and
// stays there when freed, instead of being mapped for itself and given back to the kernel.
#include "memory_policy.h"

#include <gtest/gtest.h>

#include <cstdlib>

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

}  // namespace
}  // namespace genflow
