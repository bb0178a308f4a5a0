// SPDX-License-Identifier: MIT
// genflow smooth on a real range scan (open, with holes) of $GENFLOW_DATA: every method, with and
// without a fixed boundary, writes a finite mesh of the same faces.
#include <gtest/gtest.h>

#include "cli/cli_runner.h"
#include "genflow/io/read_mesh.h"
#include "genflow/mesh/validate.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

using test::quoted;
using test::run_genflow;

TEST(SmoothCli, RealRangeScanSmoothsWithoutNanWithAndWithoutFixedBoundary) {
    const auto data = test::data_directory();
    if (!data) {
        GTEST_SKIP() << "no data directory (set GENFLOW_DATA)";
    }
    const test::TemporaryDirectory directory;
    const auto scan = *data / "smoothing" / "bun000_rangescan.ply";
    const TriangleMesh input = read_mesh(scan);
    for (const char* method : {"mcf", "fairing", "fairing2", "volume-fairing"}) {
        for (const char* fix : {"", " --fix-boundary"}) {
            const auto out = directory / "out.ply";
            const auto result = run_genflow("smooth " + quoted(scan) + " " + quoted(out) +
                                            " --steps 2 --method " + method + fix);
            ASSERT_EQ(result.exit_code, 0) << method << fix << ": " << result.err;
            const TriangleMesh smoothed = read_mesh(out);
            EXPECT_EQ(validate(smoothed).non_finite_vertices, 0) << method << fix;
            EXPECT_EQ(smoothed.F, input.F);
            if (std::string(fix).empty()) {
                EXPECT_GT((smoothed.V - input.V).norm(), 0.0) << method;
            }
        }
    }
}

}  // namespace
}  // namespace genflow
