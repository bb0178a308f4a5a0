// SPDX-License-Identifier: MIT
// Independent tasks of a match run on the OpenMP threads: the flows of the coarsest level are
// too small to split, but those from different starts or at different stiffnesses are
// independent, and so are the ZoomOuts from different sizes.
#pragma once

#include <cstddef>
#include <exception>
#include <mutex>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace genflow::detail {

/// Runs task(k) for every k < count side by side, as OpenMP tasks: tasks that run tasks side
/// by side in turn (a start's stiffness candidates) hand them to whichever thread is free, so
/// a start that ends early does not leave its thread idle while the other's candidates wait.
/// Each task runs on one thread (the team is already busy), as it would alone in a nested
/// region, so its results do not depend on how the tasks were scheduled. The first exception a
/// task threw (in time) is rethrown once all have ended. A single task runs on the calling
/// thread, which outside a team keeps both threads for it.
template <class Task>
void run_side_by_side(std::size_t count, const Task& task) {
    if (count == 0) {
        return;
    }
    if (count == 1) {
        task(0);
        return;
    }
    std::exception_ptr failure;
    std::mutex failure_mutex;
    const auto run = [&](std::size_t k) {
        try {
            task(k);
        } catch (...) {
            const std::lock_guard<std::mutex> lock(failure_mutex);
            if (!failure) {
                failure = std::current_exception();
            }
        }
    };
    const auto spawn_all = [&] {
        for (std::size_t k = 0; k < count; ++k) {
#pragma omp task default(shared) firstprivate(k)
            run(k);
        }
    };
#ifdef _OPENMP
    if (omp_in_parallel() != 0) {
        spawn_all();
#pragma omp taskwait
    } else {
        // The threads wait for the tasks at the region's barrier, where each runs any task of
        // the team, nested ones too. At a taskwait libgomp runs only the waiting task's own
        // children, which left the spawning thread idle while the other worked through a
        // sibling's nested tasks one by one (docs/benchmarks.md, "Speed").
#pragma omp parallel
#pragma omp single nowait
        spawn_all();
    }
#else
    spawn_all();
#endif
    if (failure) {
        std::rethrow_exception(failure);
    }
}

}  // namespace genflow::detail
