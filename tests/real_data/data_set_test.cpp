// SPDX-License-Identifier: MIT
// `genflow info` on every mesh of the shared data set ($GENFLOW_DATA): it must succeed and its
// counts must match manifest.json. Skipped, with a message, when the data is absent.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/cli_runner.h"

namespace genflow {
namespace {

TEST(DataSet, InfoMatchesTheManifestForEveryMesh) {
    const auto data = test::data_directory();
    if (!data) {
        GTEST_SKIP() << "no data directory (set GENFLOW_DATA); skipping the real-mesh checks";
    }
    std::ifstream manifest_file(*data / "manifest.json");
    ASSERT_TRUE(manifest_file) << "no manifest.json in " << data->string();
    const auto manifest = nlohmann::json::parse(manifest_file);
    int meshes = 0;
    for (const auto& [name, entry] : manifest.items()) {
        if (!entry.contains("vertices") || !entry.contains("faces")) {
            continue;  // labels, weights, rigs
        }
        ++meshes;
        const auto result = test::run_genflow("info --json " + test::quoted(*data / name));
        ASSERT_EQ(result.exit_code, 0) << name << ": " << result.err;
        const auto info = nlohmann::json::parse(result.out);
        EXPECT_EQ(info["vertices"], entry["vertices"]) << name;
        EXPECT_EQ(info["faces"], entry["faces"]) << name;
        EXPECT_EQ(info["validation"]["boundary_edges"], entry["boundary_edges"]) << name;
        EXPECT_EQ(info["components"], entry["components"]) << name;
        for (int axis = 0; axis < 3; ++axis) {
            const double extent =
                info["bbox_max"][axis].get<double>() - info["bbox_min"][axis].get<double>();
            EXPECT_NEAR(extent, entry["bbox"][axis].get<double>(),
                        1e-4 * info["bbox_diagonal"].get<double>())
                << name << " axis " << axis;
        }
    }
    EXPECT_GT(meshes, 50);
}

}  // namespace
}  // namespace genflow
