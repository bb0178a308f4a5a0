// SPDX-License-Identifier: MIT
#include "memory_policy.h"

#if __has_include(<malloc.h>)
#include <malloc.h>  // defines __GLIBC__ where it is glibc's
#endif

namespace genflow::cli {

void keep_freed_memory() {
#if defined(__GLIBC__)
    constexpr int kLargestHeapBlock = 32 << 20;  // glibc's DEFAULT_MMAP_THRESHOLD_MAX, 64-bit
    mallopt(M_MMAP_THRESHOLD, kLargestHeapBlock);
    mallopt(M_TRIM_THRESHOLD, 2 * kLargestHeapBlock);
#endif
}

}  // namespace genflow::cli
