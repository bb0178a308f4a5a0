// SPDX-License-Identifier: MIT
#include "genflow/threads.h"

#include <string>

#include "genflow/exceptions.h"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace genflow {

void set_thread_count(int count) {
    if (count < 1) {
        throw InvalidInput("set_thread_count: needs at least one thread, got " +
                           std::to_string(count));
    }
#ifdef _OPENMP
    omp_set_num_threads(count);
#endif
}

int thread_count() {
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

}  // namespace genflow
