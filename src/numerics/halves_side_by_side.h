// SPDX-License-Identifier: MIT
// Running a split factor's two halves (SplitCholesky) side by side on the machine's two threads,
// the BLAS held to one thread meanwhile: in the caller's OpenMP team, or on two threads of their
// own where each half opens many small OpenMP regions.
#pragma once

#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif

// OpenBLAS's thread count, where OpenBLAS is the BLAS (weak: absent otherwise).
extern "C" {
void openblas_set_num_threads(int) __attribute__((weak));
int openblas_get_num_threads() __attribute__((weak));
}

namespace genflow::detail {

// Holds OpenBLAS, where it is the BLAS, to one thread while any holder lives, and gives it back
// its own count after the last. Two halves each calling a two-thread OpenBLAS ran 4.4 times
// slower than one half alone (docs/benchmarks.md, "Two halves"); and the BLAS's thread count
// changes a supernodal factor's rounding, so the halves run on one BLAS thread whether they run
// side by side or not, for the same bits either way.
class OneThreadBlas {
public:
    OneThreadBlas() {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (!is_openblas()) {
            return;
        }
        if (holders_++ == 0) {
            own_threads_ = openblas_get_num_threads();
            openblas_set_num_threads(1);
        }
    }
    ~OneThreadBlas() {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (!is_openblas()) {
            return;
        }
        if (--holders_ == 0) {
            openblas_set_num_threads(own_threads_);
        }
    }
    OneThreadBlas(const OneThreadBlas&) = delete;
    OneThreadBlas& operator=(const OneThreadBlas&) = delete;

private:
    static bool is_openblas() {
        return openblas_set_num_threads != nullptr && openblas_get_num_threads != nullptr;
    }

    static inline std::mutex mutex_;
    static inline int holders_ = 0;
    static inline int own_threads_ = 1;
};

// Runs body(h) for both halves, side by side when two threads are free and the call is not
// inside a parallel region, else one after the other. CHOLMOD's own OpenMP teams (a fixed four
// threads per large supernode, SpdSolver's factorize() says why they cost) then run on the
// calling thread: inside the region of the halves or of the caller as nested, inactive regions
// (OpenMP's default of one active level), on one thread alone in a `teams` region of one.
template <typename Body>
void for_both_halves(Body&& body) {
    const OneThreadBlas hold;
#ifdef _OPENMP
    if (!omp_in_parallel()) {
        if (omp_get_max_threads() >= 2) {
#pragma omp parallel for num_threads(2) schedule(static, 1)
            for (int h = 0; h < 2; ++h) {
                body(h);
            }
            return;
        }
#pragma omp teams num_teams(1) thread_limit(1)
        {
            body(0);
            body(1);
        }
        return;
    }
#endif
    body(0);
    body(1);
}

// Runs body(h) for both halves as for_both_halves() does, but side by side on two threads of
// their own, the caller's and a new one, each in a `teams` region of one thread, rather than in
// a team of two: CHOLMOD's supernodal factorization opens several regions a supernode, and one
// opened inside a team costs about twice one opened alone (two futex calls instead of one;
// docs/benchmarks.md, "Dear system calls"), which outweighs the new thread's start.
template <typename Body>
void for_both_halves_on_own_threads(Body&& body) {
#ifdef _OPENMP
    if (!omp_in_parallel() && omp_get_max_threads() >= 2) {
        const OneThreadBlas hold;
        // An exception may not leave an OpenMP region: it is carried out of it.
        const auto alone = [&body](int h) {
            std::exception_ptr failure;
#pragma omp teams num_teams(1) thread_limit(1)
            {
                try {
                    body(h);
                } catch (...) {
                    failure = std::current_exception();
                }
            }
            return failure;
        };
        std::exception_ptr second_failure;
        std::thread second;
        try {
            second = std::thread([&] { second_failure = alone(1); });
        } catch (const std::system_error&) {  // no thread to be had: the team's way
            for_both_halves(std::forward<Body>(body));
            return;
        }
        const std::exception_ptr first_failure = alone(0);
        second.join();
        for (const std::exception_ptr& failure : {first_failure, second_failure}) {
            if (failure) {
                std::rethrow_exception(failure);
            }
        }
        return;
    }
#endif
    for_both_halves(std::forward<Body>(body));
}

}  // namespace genflow::detail
