// SPDX-License-Identifier: MIT
// How the tool's process keeps the memory it frees. A command allocates and frees the same large
// arrays again and again (a mesh's copies, its checks' buckets, a factor's workspace); glibc's
// malloc gives blocks above 128 KiB back to the kernel when they are freed, so every new one is
// faulted in page by page again.
#pragma once

namespace genflow::cli {

/// Starts glibc's malloc where its own adaptive thresholds end: blocks up to 32 MiB come from the
/// heap and are reused, and the heap keeps up to 64 MiB of freed memory at its top (glibc's
/// ceiling for its mmap threshold and its rule of a trim threshold twice that). On a 2-core
/// virtual machine, `smooth --steps 0` on the 43K armadillo took 0.077 instead of 0.110 s, at
/// the same peak memory (docs/benchmarks.md, "Dear system calls"). Nothing where malloc is not
/// glibc's.
void keep_freed_memory();

}  // namespace genflow::cli
