// SPDX-License-Identifier: MIT
// Test runner. Debug builds trap floating-point exceptions, as libigl's tests do, so that a
// division by zero or an invalid operation (the birth of every NaN) fails at its source.
#include <gtest/gtest.h>

#ifndef NDEBUG
#include <cfenv>
#endif

int main(int argc, char** argv) {
#if !defined(NDEBUG) && defined(__GLIBC__)
    feenableexcept(FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW);
#endif
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
