// SPDX-License-Identifier: MIT
#pragma once

namespace genflow {

/// How many threads genflow's parallel sums use from now on in this process (OpenMP's
/// omp_set_num_threads; the environment's OMP_NUM_THREADS sets the start). Results do not
/// depend on it: every parallel sum is taken in a fixed order. Several processes sharing a
/// machine (shards of a batch) each take their share this way.
/// \throws InvalidInput unless count ≥ 1.
void set_thread_count(int count);

/// The number of threads genflow's parallel sums use: 1 in a build without OpenMP.
[[nodiscard]] int thread_count();

}  // namespace genflow
