// SPDX-License-Identifier: MIT
// genflow batch: one template onto a directory or list of targets, failures recorded, the same
// results as genflow match, --resume and --shard.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli/cli_runner.h"
#include "genflow/io/read_file.h"
#include "genflow/io/write_mesh.h"
#include "genflow/mesh/primitives.h"

namespace genflow {
namespace {

using test::quoted;
using test::run_genflow;

// The JSONL record's lines, parsed.
std::vector<nlohmann::json> records(const std::filesystem::path& path) {
    std::vector<nlohmann::json> lines;
    std::ifstream file(path);
    for (std::string line; std::getline(file, line);) {
        lines.push_back(nlohmann::json::parse(line));
    }
    return lines;
}

class Batch : public ::testing::Test {
protected:
    // A template limb, three limbs sampled elsewhere and turned about different axes, and a file
    // that is no mesh at all.
    void SetUp() override {
        write_mesh(directory / "template.ply", make_limb(3));
        std::filesystem::create_directory(directory / "targets");
        const Eigen::Vector3d axes[] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                        Eigen::Vector3d::UnitZ()};
        for (int k = 0; k < 3; ++k) {
            TriangleMesh target = make_limb(3, static_cast<std::uint64_t>(k + 1));
            target.V = target.V * Eigen::AngleAxisd(0.3 * (k + 1), axes[k]).toRotationMatrix();
            write_mesh(directory / "targets" / ("pose" + std::to_string(k) + ".ply"), target);
        }
        std::ofstream(directory / "targets" / "broken.off") << "OFF\n3 1 0\n0 0 0\n";
    }

    test::CliResult batch(const std::string& extra) const {
        return run_genflow("batch " + quoted(directory / "template.ply") + " --targets " +
                           quoted(directory / "targets") + " --prior rigid --iterations 30 " +
                           extra);
    }

    const test::TemporaryDirectory directory;
};

TEST_F(Batch, MatchesEveryTargetRecordsTheFailedOneAndGoesOn) {
    const auto result = batch("--output-dir " + quoted(directory / "out"));
    EXPECT_EQ(result.exit_code, 1) << result.err;  // one target failed
    const std::vector<nlohmann::json> lines = records(directory / "out" / "batch.jsonl");
    ASSERT_EQ(lines.size(), 4U);
    EXPECT_EQ(lines[0]["name"], "broken");  // by file name
    EXPECT_EQ(lines[0]["status"], "failed");
    EXPECT_NE(lines[0]["error"].get<std::string>().find("broken.off"), std::string::npos);
    for (std::size_t k = 1; k < 4; ++k) {
        EXPECT_EQ(lines[k]["status"], "matched") << lines[k];
        EXPECT_LT(lines[k]["mean_distance_over_diagonal"].get<double>(), 0.01);
        EXPECT_EQ(lines[k]["genflow"], "0.1.0");
        EXPECT_NE(lines[k]["command_line"].get<std::string>().find("--prior rigid"),
                  std::string::npos);
        const std::string name = lines[k]["name"];
        for (const std::string& file :
             {name + ".ply", name + ".correspondence.txt", name + ".json"}) {
            EXPECT_TRUE(std::filesystem::exists(directory / "out" / file)) << file;
        }
    }
    EXPECT_FALSE(std::filesystem::exists(directory / "out" / "broken.ply"));
    // The same bytes as genflow match with the same options.
    const auto single =
        run_genflow("match " + quoted(directory / "template.ply") + " " +
                    quoted(directory / "targets" / "pose1.ply") + " -o " +
                    quoted(directory / "single.ply") + " --correspondence " +
                    quoted(directory / "single.txt") + " --prior rigid --iterations 30 --quiet");
    ASSERT_EQ(single.exit_code, 0) << single.err;
    EXPECT_EQ(read_file(directory / "single.ply"), read_file(directory / "out" / "pose1.ply"));
    EXPECT_EQ(read_file(directory / "single.txt"),
              read_file(directory / "out" / "pose1.correspondence.txt"));
}

TEST_F(Batch, ResumeSkipsTheTargetsAnEarlierRunFinished) {
    ASSERT_EQ(batch("--output-dir " + quoted(directory / "out")).exit_code, 1);
    const auto before = std::filesystem::last_write_time(directory / "out" / "pose0.ply");
    const auto again = batch("--output-dir " + quoted(directory / "out") + " --resume");
    EXPECT_EQ(again.exit_code, 1);  // the broken target fails again
    const std::vector<nlohmann::json> lines = records(directory / "out" / "batch.jsonl");
    ASSERT_EQ(lines.size(), 4U);
    EXPECT_EQ(lines[0]["status"], "failed");
    for (std::size_t k = 1; k < 4; ++k) {
        EXPECT_EQ(lines[k]["status"], "done before") << lines[k];
    }
    EXPECT_EQ(std::filesystem::last_write_time(directory / "out" / "pose0.ply"), before);
}

TEST_F(Batch, ShardsShareTheTargetsOnce) {
    std::filesystem::remove(directory / "targets" / "broken.off");
    std::set<std::string> names;
    for (const char* shard : {"0/2", "1/2"}) {
        const auto result =
            batch("--output-dir " + quoted(directory / "out") + " --shard " + shard);
        ASSERT_EQ(result.exit_code, 0) << result.err;
        const std::string index(1, shard[0]);
        for (const nlohmann::json& line :
             records(directory / "out" / ("batch." + index + "-of-2.jsonl"))) {
            EXPECT_TRUE(names.insert(line["name"].get<std::string>()).second) << line["name"];
        }
    }
    EXPECT_EQ(names, (std::set<std::string>{"pose0", "pose1", "pose2"}));
}

TEST_F(Batch, RefusesTargetsItCannotTellApartBeforeAnyWork) {
    std::ofstream(directory / "list.txt") << "# two files, one name\ntargets/pose0.ply\n"
                                             "targets/pose0.obj\n";
    write_mesh(directory / "targets" / "pose0.obj", make_limb(3));
    const auto twice =
        run_genflow("batch " + quoted(directory / "template.ply") + " --targets " +
                    quoted(directory / "list.txt") + " --output-dir " + quoted(directory / "out"));
    EXPECT_EQ(twice.exit_code, 2);
    EXPECT_NE(twice.err.find("two targets are named \"pose0\""), std::string::npos) << twice.err;
    EXPECT_FALSE(std::filesystem::exists(directory / "out"));
    const auto nowhere =
        run_genflow("batch " + quoted(directory / "template.ply") + " --targets " +
                    quoted(directory / "nosuch") + " --output-dir " + quoted(directory / "out"));
    EXPECT_EQ(nowhere.exit_code, 2);
    EXPECT_NE(nowhere.err.find("nosuch: no such directory or list file"), std::string::npos);
}

// The articulated prior's part model is read once with the template and given to every target,
// as `genflow match --parts` would use it.
TEST_F(Batch, TakesThePartModelOfTheArticulatedPrior) {
    std::ofstream(directory / "parts.json")
        << R"({"parts": [{"name": "middle", "parent": null, "joint_center": [0, 0, 0]},)"
        << R"( {"name": "front", "parent": "middle", "joint_center": [1.0, 0, 0]}]})";
    const TriangleMesh limb = make_limb(3);
    std::ofstream labels(directory / "labels.txt");
    for (Eigen::Index i = 0; i < limb.V.rows(); ++i) {
        labels << (limb.V(i, 0) > 1.0 ? 1 : 0) << "\n";
    }
    labels.close();
    std::ofstream(directory / "list.txt") << "targets/pose1.ply\n";
    const std::string parts = " --parts " + quoted(directory / "parts.json") + " --part-labels " +
                              quoted(directory / "labels.txt") + " --iterations 10";
    const auto batched = run_genflow("batch " + quoted(directory / "template.ply") + " --targets " +
                                     quoted(directory / "list.txt") + " --output-dir " +
                                     quoted(directory / "out") + parts);
    ASSERT_EQ(batched.exit_code, 0) << batched.err;
    const auto single = run_genflow("match " + quoted(directory / "template.ply") + " " +
                                    quoted(directory / "targets" / "pose1.ply") + " -o " +
                                    quoted(directory / "single.ply") + parts + " --quiet");
    ASSERT_EQ(single.exit_code, 0) << single.err;
    EXPECT_EQ(read_file(directory / "single.ply"), read_file(directory / "out" / "pose1.ply"));
    const nlohmann::json summary =
        nlohmann::json::parse(read_file(directory / "out" / "pose1.json"));
    EXPECT_EQ(summary["prior"], "articulated");  // the default with a part model

    const auto without = run_genflow("batch " + quoted(directory / "template.ply") + " --targets " +
                                     quoted(directory / "list.txt") + " --output-dir " +
                                     quoted(directory / "none") + " --prior articulated");
    EXPECT_EQ(without.exit_code, 2);
    EXPECT_NE(without.err.find("--prior articulated needs --parts"), std::string::npos)
        << without.err;
    EXPECT_FALSE(std::filesystem::exists(directory / "none"));
}

TEST_F(Batch, RefusesAListLineThatNamesNoMeshOrPointFile) {
    std::ofstream(directory / "list.txt") << "targets/pose0.ply\n\ntargets/notes.txt\n";
    const auto listed =
        run_genflow("batch " + quoted(directory / "template.ply") + " --targets " +
                    quoted(directory / "list.txt") + " --output-dir " + quoted(directory / "out"));
    EXPECT_EQ(listed.exit_code, 2);
    EXPECT_NE(listed.err.find("list.txt: line 3: 'targets/notes.txt' is not a mesh or point file"),
              std::string::npos)
        << listed.err;
    EXPECT_FALSE(std::filesystem::exists(directory / "out"));
}

}  // namespace
}  // namespace genflow
