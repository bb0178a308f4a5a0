// SPDX-License-Identifier: MIT
// genflow used as a hostile or careless user would: bad files, bad option values, outputs that
// cannot be written, names that try to leave their directory, signals, other thread counts.
// Each refusal is one line naming the file or option and the problem, with the documented exit
// code (docs/cli.md), and leaves every file as it was.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_runner.h"
#include "genflow/io/read_mesh.h"
#include "genflow/io/write_mesh.h"
#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

using test::quoted;

// The PLY header of `vertices` float vertices and `faces` triangles, in `format`.
std::string ply_header(const std::string& format, long vertices, long faces) {
    return "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(vertices) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
           std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

// A directory of good and bad inputs, named as the commands below use them.
class HostileInput : public ::testing::Test {
protected:
    void SetUp() override {
        write_mesh(directory / "s.ply", make_icosphere(1));
        write_mesh(directory / "limb.ply", make_limb(2));
        test::write_bytes(directory / "p.ply", "old");  // an output that must survive failures
        ASSERT_EQ(::mkfifo((directory / "f.ply").c_str(), 0600), 0);
        test::write_bytes(directory / "big.ply",
                          ply_header("ascii", 3, 1) + "0 0 0\n1e308 0 0\n0 1 0\n3 0 1 2\n");
        test::write_bytes(directory / "declared.ply",
                          ply_header("binary_little_endian", 200000000, 1) + "0123456789ab");
        test::write_bytes(directory / "trailing.ply",
                          ply_header("ascii", 3, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n");
        test::write_bytes(directory / "fewer.off",
                          "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 3\n");
        test::write_bytes(directory / "flat.off",
                          "OFF\n4 2 0\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n3 0 1 2\n3 1 2 3\n");
        std::filesystem::create_directory(directory / "adir.ply");
        write_pairs("pairs.json", {pair("limb")});
        write_pairs("up.json", {pair("../x")});
        write_pairs("escape.json", {pair("\x1b[2Jlimb")});
        write_pairs("twice.json", {pair("limb"), pair("limb")});
    }

    static nlohmann::json pair(const std::string& name) {
        return {{"name", name},
                {"template", "limb.ply"},
                {"target_ground_truth", "limb.ply"},
                {"target_remeshed", "limb.ply"}};
    }

    void write_pairs(const std::string& name, const std::vector<nlohmann::json>& pairs) const {
        std::ofstream(directory / name) << nlohmann::json(pairs).dump();
    }

    // The names in the directory and each regular file's bytes.
    [[nodiscard]] std::vector<std::pair<std::string, std::string>> contents() const {
        std::vector<std::pair<std::string, std::string>> entries;
        for (const auto& entry : std::filesystem::directory_iterator(directory.path())) {
            entries.emplace_back(entry.path().filename().string(),
                                 entry.is_regular_file() ? test::read_text(entry.path()) : "");
        }
        std::sort(entries.begin(), entries.end());
        return entries;
    }

    [[nodiscard]] test::CliResult run(const std::string& arguments) const {
        return test::run_genflow_after("cd " + quoted(directory.path()) + " && ", arguments);
    }

    test::TemporaryDirectory directory;
};

struct Refusal {
    std::string command;  // run in the directory of HostileInput
    int exit_code;        // docs/cli.md: 1 computation or output failure, 2 bad input
    std::string says;     // a part of the one line on standard error
};

TEST_F(HostileInput, EveryRefusalIsOneLineWithItsExitCodeAndChangesNoFile) {
    const std::vector<Refusal> refusals = {
        // Inputs that are not what they claim.
        {"info f.ply", 2, "f.ply: not a regular file"},
        {"info big.ply", 2, "big.ply: 1 vertices with a coordinate beyond ±1e50"},
        {"distance big.ply s.ply", 2, "big.ply: 1 vertices with a coordinate beyond ±1e50"},
        {"info declared.ply", 2,
         "declared.ply: element 'vertex' declares 200000000 items, more than the file can hold"},
        {"info trailing.ply", 2, "trailing.ply: more data than the header declares"},
        {"info fewer.off", 2,
         "fewer.off: line 8: more data than the header's 4 vertices and 1 faces"},
        {"smooth flat.off o.ply", 2, "flat.off: every face has zero area"},
        {"distance s.ply flat.off", 2, "flat.off: every face has zero area"},
        {"match flat.off s.ply -o o.ply", 2, "flat.off: every face has zero area"},
        // Option values.
        {"distance s.ply s.ply --eps 1e300", 2,
         "--eps: must be a positive length up to 1e+50, got 1e300"},
        {"distance s.ply s.ply --eps nan", 2,
         "--eps: must be a positive length up to 1e+50, got nan"},
        {"smooth s.ply o.ply --lambda nan", 2, "--lambda: must be a positive number, got nan"},
        {"smooth s.ply o.ply --dt inf", 2, "--dt: must be a positive number, got inf"},
        {"smooth s.ply o.ply --steps 1.5", 2, "--steps: must be a whole number in range, got 1.5"},
        {"smooth s.ply o.ply --steps abc", 2, "--steps: must be a number >= 0, got abc"},
        {"match s.ply s.ply -o o.ply --rigidity-length nan", 2,
         "--rigidity-length: must be a number in [0, 10], got nan"},
        {"match s.ply s.ply -o o.ply --alpha 1e9", 2,
         "--alpha: must be a number in [0.5, 1000], got 1e9"},
        {"match s.ply s.ply -o o.ply --second-opinion-above nan", 2,
         "--second-opinion-above: must be a number >= 0 or inf, got nan"},
        {"match limb.ply limb.ply -o o.ply --parts t.json --part-labels l.txt --part-weights w.txt",
         2, "--part-labels excludes --part-weights"},
        {"match limb.ply limb.ply -o o.ply --part-labels l.txt", 2,
         "--part-labels requires --parts"},
        // Commands.
        {"frobnicate", 2, "unknown command 'frobnicate' (commands: info, smooth"},
        {"match", 2, "(run 'genflow match --help')"},
        {"eval pairs.json --pairs nosuch", 2, "pairs.json: no pair named \"nosuch\""},
        {"eval twice.json", 2, "twice.json: two pairs are named \"limb\""},
        {"eval up.json --output-dir out", 2, "up.json: a pair's name must be a plain file name"},
        {"eval escape.json", 2, "got \"\\x1b[2Jlimb\""},
        // Outputs that cannot be written, found before any work.
        {"smooth s.ply nodir/o.ply", 1, "nodir/o.ply: cannot be written: the directory"},
        {"smooth s.ply adir.ply", 1, "adir.ply: is a directory"},
        {"match limb.ply limb.ply -o nodir/x.ply", 1, "x.ply: cannot be written: the directory"},
        {"match limb.ply limb.ply -o p.ply --summary nodir/s.json", 1,
         "s.json: cannot be written: the directory"},
        {"eval pairs.json --output-dir p.ply/sub", 1, "cannot create directory"},
        {"distance s.ply s.ply --colored nodir/c.ply", 1,
         "c.ply: cannot be written: the directory"},
        {"distance s.ply s.ply --colored c.xyz", 2, "c.xyz: cannot write this format"},
        {"smooth s.ply o.ply --report r.txt", 2, "r.txt: a report is an HTML page"},
        {"distance s.ply s.ply --threads 0", 2, "--threads: must be a positive number, got 0"},
        {"smooth s.ply o.ply --frames nodir/a.glb", 1, "a.glb: cannot be written: the directory"},
        {"distance s.ply s.ply --report nodir/r.html", 1,
         "r.html: cannot be written: the directory"},
        {"match limb.ply limb.ply -o o.ply --report r.ply", 2, "r.ply: a report is an HTML page"},
    };
    const auto before = contents();
    for (const Refusal& refusal : refusals) {
        const test::CliResult result = run(refusal.command);
        EXPECT_EQ(result.exit_code, refusal.exit_code) << refusal.command << ": " << result.err;
        EXPECT_NE(result.err.find(refusal.says), std::string::npos)
            << refusal.command << ": " << result.err;
        EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1)
            << refusal.command << ": " << result.err;
        EXPECT_EQ(contents(), before) << refusal.command;
    }
}

// A file's name is printed with its control characters escaped: a newline or an escape
// sequence in it cannot split the message or drive the terminal.
TEST_F(HostileInput, FileNamesArePrintedWithControlCharactersEscaped) {
    test::write_bytes(directory / "a\nb\x1b[31m.ply", "");
    const test::CliResult result = run("info " + quoted("a\nb\x1b[31m.ply"));
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.err, "genflow: a\\nb\\x1b[31m.ply: empty file\n");
}

// A UTF-8 byte order mark, as some editors write, hid the first vertex of an OBJ file: every
// index shifted by one.
TEST_F(HostileInput, AByteOrderMarkIsSkipped) {
    test::write_bytes(directory / "bom.obj",
                      "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\n");
    const test::CliResult result = run("info --json bom.obj");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(nlohmann::json::parse(result.out)["vertices"], 4);
}

// An existing output keeps its mode; a symbolic link is written through (the file it points to
// is replaced, the link stays).
TEST_F(HostileInput, AnOutputKeepsItsModeAndItsLink) {
    ASSERT_EQ(::chmod((directory / "p.ply").c_str(), 0600), 0);
    std::filesystem::create_symlink("linked.ply", directory / "link.ply");
    for (const char* output : {"p.ply", "link.ply"}) {
        const test::CliResult result = run(std::string("smooth s.ply ") + output + " --steps 1");
        ASSERT_EQ(result.exit_code, 0) << result.err;
    }
    EXPECT_EQ(std::filesystem::status(directory / "p.ply").permissions(),
              std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
    EXPECT_EQ(read_mesh(directory / "p.ply").V.rows(), 42);
    EXPECT_TRUE(std::filesystem::is_symlink(directory / "link.ply"));
    EXPECT_EQ(read_mesh(directory / "linked.ply").V.rows(), 42);
}

// Ended by a signal while it writes frames, a run leaves no temporary behind (whatever it had
// written completely stays).
TEST_F(HostileInput, ASignalDuringTheWritesLeavesNoTemporary) {
    write_mesh(directory / "large.ply", make_icosphere(6));
    const test::CliResult result =
        test::run_genflow_after("cd " + quoted(directory.path()) + "; (sleep 1; kill $$) & exec ",
                                "smooth large.ply o.ply --steps 200 --frames frames");
    EXPECT_EQ(result.exit_code, 128 + SIGTERM) << result.err;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(directory.path())) {
        EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
    }
}

// The same input and options give the same bytes on any number of threads: every parallel sum
// runs in an order of its own (here the pseudo-Hausdorff sums of 10K-point sides).
TEST_F(HostileInput, ResultsAreTheSameOnAnyNumberOfThreads) {
    write_mesh(directory / "a.ply", make_icosphere(5));
    write_mesh(directory / "b.ply", test::noisy_icosphere(5, 0.2));
    std::vector<std::string> outputs;
    for (const char* threads : {"1", "2", "3"}) {
        const test::CliResult result = test::run_genflow_after(
            "cd " + quoted(directory.path()) + " && OMP_NUM_THREADS=" + threads + " ",
            "distance a.ply b.ply --json");
        ASSERT_EQ(result.exit_code, 0) << result.err;
        outputs.push_back(result.out);
    }
    EXPECT_EQ(outputs[1], outputs[0]);
    EXPECT_EQ(outputs[2], outputs[0]);
    // --threads overrides the environment, after the command's options as before them.
    for (const char* where :
         {"--threads 3 distance a.ply b.ply --json", "distance a.ply b.ply --json --threads 3"}) {
        const test::CliResult result = test::run_genflow_after(
            "cd " + quoted(directory.path()) + " && OMP_NUM_THREADS=1 ", where);
        ASSERT_EQ(result.exit_code, 0) << result.err;
        EXPECT_EQ(result.out, outputs[0]) << where;
    }
}

}  // namespace
}  // namespace genflow
