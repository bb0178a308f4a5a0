// SPDX-License-Identifier: MIT
// genflow eval end to end on a generated pair file, and its refusals.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "cli/cli_runner.h"
#include "genflow/io/read_mesh.h"
#include "genflow/io/write_mesh.h"
#include "genflow/matching/correspondence_error.h"
#include "genflow/matching/rigid_alignment.h"
#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

using test::quoted;
using test::run_genflow;

// A limb and the same limb moved rigidly (its ground truth), in `directory`, with a pair file
// whose one pair has `target` for its target (a "target_remeshed" file, a
// "target_simplified" share, or neither).
std::filesystem::path write_pair(const std::filesystem::path& directory,
                                 const nlohmann::json& target) {
    const TriangleMesh limb = make_limb(3);
    Similarity motion;
    motion.rotation = Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    motion.translation = Eigen::Vector3d(0.5, -1, 2);
    write_mesh(directory / "template.ply", limb);
    write_mesh(directory / "truth.ply", TriangleMesh{motion.apply(limb.V), limb.F});
    TriangleMesh resampled = make_limb(3, 3);
    resampled.V = motion.apply(resampled.V);
    write_mesh(directory / "resampled.obj", resampled);
    nlohmann::json pair = {
        {"name", "limb"}, {"template", "template.ply"}, {"target_ground_truth", "truth.ply"}};
    pair.update(target);
    const std::filesystem::path file = directory / "pairs.json";
    std::ofstream(file) << nlohmann::json::array({pair}).dump();
    return file;
}

TEST(EvalCli, MatchesAPairAgainstItsRemeshedTarget) {
    const test::TemporaryDirectory directory;
    const auto file = write_pair(directory.path(), {{"target_remeshed", "resampled.obj"}});
    const auto result = run_genflow("eval " + quoted(file) + " --priors rigid --json");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto rows = nlohmann::json::parse(result.out);
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0]["pair"], "limb");
    EXPECT_EQ(rows[0]["prior"], "rigid");
    EXPECT_LT(rows[0]["mean"].template get<double>(), 0.02);
    EXPECT_EQ(rows[0]["stranded_vertices"], 0);
    EXPECT_EQ(rows[0]["second_opinion"], false);
    EXPECT_TRUE(rows[0]["second_opinion_disagreement"].is_null());  // the rigid prior asks none
    EXPECT_EQ(rows[0]["swapped_limbs"], 0);
    EXPECT_EQ(rows[0]["signature_fallback"], false);
}

// With --stages each row has the error after each stage: here one level, whose result is the
// match's; beside a table they go to standard error, one line per row.
TEST(EvalCli, ReportsTheErrorAfterEachStage) {
    const test::TemporaryDirectory directory;
    const auto file = write_pair(directory.path(), {{"target_remeshed", "resampled.obj"}});
    const auto json = run_genflow("eval " + quoted(file) + " --priors rigid --stages --json");
    ASSERT_EQ(json.exit_code, 0) << json.err;
    const auto rows = nlohmann::json::parse(json.out);
    ASSERT_EQ(rows.size(), 1u);
    const auto& stages = rows[0]["stages"];
    ASSERT_EQ(stages.size(), 1u) << stages.dump();
    EXPECT_EQ(stages[0]["level"], 0);
    EXPECT_EQ(stages[0]["stage"], "coarsest");
    EXPECT_EQ(stages[0]["vertices"], 642);
    EXPECT_NEAR(stages[0]["mean"].template get<double>(), rows[0]["mean"].template get<double>(),
                1e-12);

    const auto table = run_genflow("eval " + quoted(file) + " --priors rigid --stages");
    ASSERT_EQ(table.exit_code, 0) << table.err;
    EXPECT_NE(table.err.find("limb rigid: level 0 coarsest "), std::string::npos) << table.err;
    EXPECT_NE(table.out.find("| limb | rigid | "), std::string::npos) << table.out;
    EXPECT_EQ(run_genflow("eval " + quoted(file) + " --priors rigid --json").out.find("\"stages\""),
              std::string::npos);  // only when asked
}

// The matcher's algorithm flags are `genflow match`'s: here two levels where the default
// makes one of the 642-vertex limb, so the stages come from both.
TEST(EvalCli, TakesTheMatchersAlgorithmFlags) {
    const test::TemporaryDirectory directory;
    const auto file = write_pair(directory.path(), {{"target_remeshed", "resampled.obj"}});
    const auto result =
        run_genflow("eval " + quoted(file) + " --priors rigid --levels 2 --stages --json");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto rows = nlohmann::json::parse(result.out);
    ASSERT_EQ(rows.size(), 1u);
    std::set<int> levels;
    for (const auto& stage : rows[0]["stages"]) {
        levels.insert(stage["level"].template get<int>());
    }
    EXPECT_EQ(levels, (std::set<int>{0, 1})) << rows[0]["stages"].dump();
    EXPECT_LT(rows[0]["mean"].template get<double>(), 0.05);  // from a coarser start, still near
}

TEST(EvalCli, MatchesAPairAgainstItsGroundTruthSimplified) {
    const test::TemporaryDirectory directory;
    const auto file = write_pair(directory.path(), {{"target_simplified", 0.6}});
    // As a table this time: the pair's row and its mean error, below 2 %.
    const auto result = run_genflow("eval " + quoted(file) + " --priors rigid");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const std::size_t row = result.out.find("| limb | rigid | ");
    ASSERT_NE(row, std::string::npos) << result.out;
    std::istringstream cells(result.out.substr(row + 17));
    double mean = 100;
    std::string percent;
    cells >> mean >> percent;
    EXPECT_LT(mean, 2) << result.out;
    EXPECT_EQ(percent, "%");
}

TEST(EvalCli, WritesTheTargetAsMatchedAndTheResultToTheOutputDirectory) {
    const test::TemporaryDirectory directory;
    const auto file = write_pair(directory.path(), {{"target_simplified", 0.6}});
    const auto out = directory.path() / "results" / "limb";
    const auto result =
        run_genflow("eval " + quoted(file) + " --priors rigid --output-dir " + quoted(out));
    ASSERT_EQ(result.exit_code, 0) << result.err;
    // The simplified target has about 60 % of the truth's vertices (coarsen() may stop a few
    // collapses short); the result has the template's vertices and faces, and lies where the
    // truth does.
    const TriangleMesh truth = read_mesh(directory.path() / "truth.ply");
    const TriangleMesh target = read_mesh(out / "limb.target.ply");
    EXPECT_NEAR(static_cast<double>(target.V.rows()), 0.6 * static_cast<double>(truth.V.rows()),
                0.01 * static_cast<double>(truth.V.rows()));
    const TriangleMesh deformed = read_mesh(out / "limb.rigid.ply");
    ASSERT_EQ(deformed.V.rows(), truth.V.rows());
    EXPECT_EQ(deformed.F, truth.F);
    EXPECT_LT(correspondence_error(deformed.V, truth).mean, 0.02);
    // With each vertex's distance to the target and its error against the truth.
    VertexAttributes values;
    (void)read_mesh(out / "limb.rigid.ply", nullptr, &values);
    ASSERT_EQ(values.scalars.size(), 2U);
    EXPECT_EQ(values.scalars[0].first, "distance");
    EXPECT_EQ(values.scalars[1].first, "error");
    EXPECT_EQ(values.scalars[1].second, (deformed.V - truth.V).rowwise().norm());
}

TEST(EvalCli, RefusesAnOutputDirectoryItCannotCreateBeforeMatching) {
    const test::TemporaryDirectory directory;
    const auto file = write_pair(directory.path(), {{"target_remeshed", "resampled.obj"}});
    const auto blocked = directory.path() / "template.ply" / "results";  // under a file
    const auto result =
        run_genflow("eval " + quoted(file) + " --priors rigid --output-dir " + quoted(blocked));
    EXPECT_EQ(result.exit_code, 1);  // an output that cannot be written
    EXPECT_NE(result.err.find(blocked.string() + ": cannot create directory"), std::string::npos)
        << result.err;
    EXPECT_EQ(result.out.find("| limb |"), std::string::npos) << result.out;
}

// A pair's name names its files in the output directory: one that would lead out of it is
// refused before anything is matched or written.
TEST(EvalCli, RefusesAPairNameThatLeavesTheOutputDirectory) {
    for (const std::string name : {"../x", "/tmp/x", "a/b", ".hidden", ""}) {
        const test::TemporaryDirectory directory;
        const auto file =
            write_pair(directory.path(), {{"target_remeshed", "resampled.obj"}, {"name", name}});
        const auto out = directory.path() / "out";
        const auto result =
            run_genflow("eval " + quoted(file) + " --priors rigid --output-dir " + quoted(out));
        EXPECT_EQ(result.exit_code, 2) << name;
        EXPECT_NE(result.err.find("a pair's name must be a plain file name"), std::string::npos)
            << result.err;
        EXPECT_FALSE(std::filesystem::exists(directory.path() / "x.target.ply")) << name;
        EXPECT_TRUE(!std::filesystem::exists(out) || std::filesystem::is_empty(out)) << name;
    }
}

TEST(EvalCli, RefusesAPairWithoutATargetOrWithABadShare) {
    for (const nlohmann::json& target :
         {nlohmann::json::object(), nlohmann::json{{"target_simplified", 1.5}},
          nlohmann::json{{"target_simplified", "half"}}}) {
        const test::TemporaryDirectory directory;
        const auto file = write_pair(directory.path(), target);
        const auto result = run_genflow("eval " + quoted(file) + " --priors rigid");
        EXPECT_EQ(result.exit_code, 2) << target.dump();
        EXPECT_NE(result.err.find("pairs.json: pair limb"), std::string::npos) << result.err;
    }
}

}  // namespace
}  // namespace genflow
