// SPDX-License-Identifier: MIT
#include "genflow/threads.h"

#include <gtest/gtest.h>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/exceptions.h"
#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// The count is what the sums then use (OpenMP builds), and the results do not depend on it.
TEST(Threads, SetTheCountTheSumsUseWithoutChangingTheirResults) {
    const int before = thread_count();
    const TriangleMesh target = make_icosphere(4);
    const TriangleMesh moving = test::noisy_icosphere(4, 0.2);
    const PseudoHausdorffEnergy energy(target, {.alpha = 8, .epsilon = 0.05});
    std::vector<double> values;
    for (const int count : {1, 3}) {
        set_thread_count(count);
#ifdef _OPENMP
        EXPECT_EQ(thread_count(), count);
#else
        EXPECT_EQ(thread_count(), 1);
#endif
        values.push_back(energy.value(moving));
    }
    EXPECT_EQ(values[0], values[1]);
    EXPECT_THROW(set_thread_count(0), InvalidInput);
    set_thread_count(before);
}

}  // namespace
}  // namespace genflow
