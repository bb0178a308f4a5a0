// SPDX-License-Identifier: MIT
// genflow match end to end on a generated pair, and its refusals.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "cli/cli_runner.h"
#include "genflow/evaluation/single_view.h"
#include "genflow/io/read_file.h"
#include "genflow/io/read_mesh.h"
#include "genflow/io/write_mesh.h"
#include "genflow/matching/rigid_alignment.h"
#include "genflow/mesh/primitives.h"
#include "genflow/operators/normals.h"

namespace genflow {
namespace {

using test::quoted;
using test::run_genflow;

// A limb and a finer limb moved rigidly: a pair whose answer is known (the template moved as
// the target was).
struct MovedLimbs {
    TriangleMesh template_mesh = make_limb(3);
    TriangleMesh target_at_rest = make_limb(4, 5);
    Similarity motion;
    TriangleMesh target;

    MovedLimbs(const Eigen::AngleAxisd& rotation, const Eigen::Vector3d& translation) {
        motion.rotation = rotation.toRotationMatrix();
        motion.translation = translation;
        target = TriangleMesh{motion.apply(target_at_rest.V), target_at_rest.F};
    }
};

TEST(MatchCli, WritesTheDeformedTemplateCorrespondencesFramesAndSummary) {
    const test::TemporaryDirectory directory;
    const MovedLimbs pair(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitY()), {1, 2, 3});
    const TriangleMesh& template_mesh = pair.template_mesh;
    const TriangleMesh& target = pair.target;
    const Similarity& motion = pair.motion;
    VertexAttributes painted;  // the template's colours go with it onto the target
    painted.colors = VertexColors::Zero(template_mesh.V.rows(), 3);
    painted.colors.col(2) = (template_mesh.V.col(0).array() > 0).cast<std::uint8_t>() * 200;
    write_mesh(directory / "template.ply", template_mesh, painted);
    write_mesh(directory / "target.obj", target);
    // The template moved as the target was: where each of its vertices belongs.
    write_mesh(directory / "truth.ply",
               TriangleMesh{motion.apply(template_mesh.V), template_mesh.F});
    const auto result = run_genflow(
        "match " + quoted(directory / "template.ply") + " " + quoted(directory / "target.obj") +
        " -o " + quoted(directory / "out.ply") +
        " --prior rigid --iterations 60 --correspondence " + quoted(directory / "corr.txt") +
        " --frames " + quoted(directory / "frames") + " --summary " +
        quoted(directory / "summary.json") + " --ground-truth " + quoted(directory / "truth.ply") +
        " --colored " + quoted(directory / "colored.ply") + " --json");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto json = nlohmann::json::parse(result.out);
    EXPECT_EQ(json["prior"], "rigid");
    EXPECT_EQ(json["genflow"], "0.1.0");  // what made it, and how
    EXPECT_NE(json["command_line"].get<std::string>().find("--prior rigid --iterations 60"),
              std::string::npos);
    EXPECT_LT(json["mean_distance_over_diagonal"].get<double>(), 0.01);
    EXPECT_LT(json["hausdorff_over_diagonal"].get<double>(), 0.05);
    EXPECT_EQ(json["levels"].size(), 1u);
    // The energy after each step of the level's kept flow, and with the ground truth the error
    // after each stage.
    const auto& trace = json["levels"][0]["pseudo_hausdorff_per_step"];
    ASSERT_GE(trace.size(), 2u);
    EXPECT_LE(trace.size(), json["levels"][0]["iterations"].get<std::size_t>() + 1);
    EXPECT_EQ(trace.front(), json["levels"][0]["pseudo_hausdorff_start"]);
    EXPECT_EQ(trace.back(), json["levels"][0]["pseudo_hausdorff_end"]);
    ASSERT_FALSE(json["stages"].empty());
    EXPECT_EQ(json["stages"].back()["level"], 0);
    EXPECT_LT(json["stages"].back()["mean"].get<double>(), 0.02);
    EXPECT_EQ(json["turned_parts"], 0);  // the rigid prior has no refinement to turn back
    EXPECT_EQ(json["map_fits"], 0);      // nor to fit to the fine map
    EXPECT_GT(json["intrinsic_disagreement"].get<double>(), 0);
    EXPECT_EQ(json["doubtful"], false);
    EXPECT_EQ(json["second_opinion"], false);
    EXPECT_TRUE(json["second_opinion_disagreement"].is_null());  // the rigid prior asks none
    EXPECT_EQ(json["swapped_limbs"], 0);                         // nor checks for swapped limbs
    EXPECT_EQ(json["signature_fallback"], false);                // nor has a guided round
    EXPECT_GE(json["counterparts_moved"].get<long>(), 0);        // the counterparts, by default
    EXPECT_LT(json["correspondence_error_over_diagonal"]["mean"].get<double>(), 0.02);
    EXPECT_EQ(json["stranded_vertices"], 0);
    EXPECT_TRUE(json["stranded_vertex_indices"].empty());
    EXPECT_LT(json["reversed_area"].get<double>(), 0.01);
    const TriangleMesh out = read_mesh(directory / "out.ply");
    EXPECT_EQ(out.F, template_mesh.F);
    std::ifstream correspondences(directory / "corr.txt");
    int lines = 0;
    for (std::string line; std::getline(correspondences, line);) {
        lines += line.empty() || line[0] == '#' ? 0 : 1;
    }
    EXPECT_EQ(lines, template_mesh.V.rows());
    EXPECT_TRUE(std::filesystem::exists(directory / "frames" / "frame_00000.ply"));
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(directory / "summary.json")), json);
    // The output's rows: x, y, z, each vertex's distance to the target and its error, and the
    // template's colour.
    const std::string bytes = read_file(directory / "out.ply");
    ASSERT_NE(bytes.find("property double distance\nproperty double error\nproperty uchar red"),
              std::string::npos);
    VertexAttributes carried;
    (void)read_mesh(directory / "out.ply", nullptr, &carried);
    EXPECT_EQ(carried.colors, painted.colors);
    const char* rows = bytes.data() + bytes.find("end_header\n") + 11;
    const TriangleMesh truth = read_mesh(directory / "truth.ply");
    double error_sum = 0;
    double largest_error = 0;
    for (Eigen::Index i = 0; i < out.V.rows(); ++i) {
        double values[5];
        std::memcpy(values, rows + 43 * i, sizeof values);
        EXPECT_EQ(values[0], out.V(i, 0));
        EXPECT_LE(values[3], json["hausdorff"].get<double>());
        EXPECT_DOUBLE_EQ(values[4], (out.V.row(i) - truth.V.row(i)).norm());
        error_sum += values[4];
        largest_error = std::max(largest_error, values[4]);
    }
    const double diagonal = (truth.V.colwise().maxCoeff() - truth.V.colwise().minCoeff()).norm();
    EXPECT_NEAR(error_sum / static_cast<double>(out.V.rows()) / diagonal,
                json["correspondence_error_over_diagonal"]["mean"].get<double>(), 1e-12);
    // --colored: the same mesh, coloured by the error from 0 to its largest.
    EXPECT_EQ(json["colored"]["property"], "error");
    EXPECT_DOUBLE_EQ(json["colored"]["scale"][1].get<double>(), largest_error);
    EXPECT_EQ(read_mesh(directory / "colored.ply").V, out.V);
    EXPECT_NE(read_file(directory / "colored.ply").find("property uchar red"), std::string::npos);
}

// The template's texture coordinates go with it, per corner where its file has them so.
TEST(MatchCli, KeepsTheTemplatesTextureCoordinates) {
    const test::TemporaryDirectory directory;
    const MovedLimbs pair(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()), {0, 1, 0});
    const TriangleMesh& limb = pair.template_mesh;
    VertexAttributes textured;  // each face its own patch: every edge a seam
    textured.corner_uvs.resize(3 * limb.F.rows(), 2);
    textured.corner_uv_faces.resize(limb.F.rows(), 3);
    for (Eigen::Index f = 0; f < limb.F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            textured.corner_uv_faces(f, c) = static_cast<int>(3 * f + c);
            textured.corner_uvs.row(3 * f + c) << static_cast<double>(f) / limb.F.rows(), c / 2.0;
        }
    }
    write_mesh(directory / "template.obj", limb, textured);
    write_mesh(directory / "target.ply", pair.target);
    const auto result = run_genflow(
        "match " + quoted(directory / "template.obj") + " " + quoted(directory / "target.ply") +
        " -o " + quoted(directory / "out.obj") + " --prior rigid --iterations 5 --quiet");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    VertexAttributes kept;
    const TriangleMesh out = read_mesh(directory / "out.obj", nullptr, &kept);
    EXPECT_EQ(out.F, limb.F);
    EXPECT_EQ(kept.corner_uv_faces, textured.corner_uv_faces);
    EXPECT_EQ(kept.corner_uvs, textured.corner_uvs);
}

// A painted template matched onto a moved and resampled copy of itself hands its colours,
// labels and values to the target's vertices through the correspondence file: a label comes
// whole from the nearest corner, a value interpolated.
TEST(MatchCli, TransferCarriesTheTemplatesAttributesToTheTarget) {
    const test::TemporaryDirectory directory;
    const MovedLimbs pair(Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitZ()), {2, 0, 1});
    const TriangleMesh& limb = pair.template_mesh;
    const TriangleMesh& target = pair.target;
    const Eigen::MatrixX3d& target_at_rest = pair.target_at_rest.V;
    const Eigen::Index axis = 0;
    const double middle = limb.V.col(axis).mean();
    VertexAttributes painted;
    painted.colors = VertexColors::Zero(limb.V.rows(), 3);
    painted.colors.col(0) = (limb.V.col(axis).array() > middle).cast<std::uint8_t>() * 255;
    painted.scalars.emplace_back("part", (limb.V.col(axis).array() > middle).cast<double>());
    painted.scalars.emplace_back("height", limb.V.col(axis));
    write_mesh(directory / "template.ply", limb, painted);
    write_mesh(directory / "target.ply", target);
    const auto matched =
        run_genflow("match " + quoted(directory / "template.ply") + " " +
                    quoted(directory / "target.ply") + " -o " + quoted(directory / "out.ply") +
                    " --prior rigid --iterations 60 --quiet "
                    "--correspondence " +
                    quoted(directory / "map.txt"));
    ASSERT_EQ(matched.exit_code, 0) << matched.err;
    const auto result = run_genflow(
        "transfer " + quoted(directory / "template.ply") + " " + quoted(directory / "target.ply") +
        " " + quoted(directory / "map.txt") + " -o " + quoted(directory / "painted.ply"));
    ASSERT_EQ(result.exit_code, 0) << result.err;
    VertexAttributes carried;
    const TriangleMesh out = read_mesh(directory / "painted.ply", nullptr, &carried);
    EXPECT_EQ(out.V, target.V);
    ASSERT_EQ(carried.colors.rows(), target.V.rows());
    ASSERT_EQ(carried.scalars.size(), 2U);
    const double extent = limb.V.col(axis).maxCoeff() - limb.V.col(axis).minCoeff();
    int wrong = 0;
    double height_error = 0;
    for (Eigen::Index t = 0; t < target.V.rows(); ++t) {
        const double height = target_at_rest(t, axis);
        const double part = carried.scalars[0].second[t];
        EXPECT_TRUE(part == 0 || part == 1) << part;  // a label, never a blend
        if (std::abs(height - middle) > 0.05 * extent) {
            wrong += (part == 1) != (height > middle) ? 1 : 0;
            // Colours are interpolated: blended across the faces that straddle the middle.
            EXPECT_EQ(carried.colors(t, 0) > 127, part == 1) << int(carried.colors(t, 0));
        }
        height_error += std::abs(carried.scalars[1].second[t] - height);
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_LT(height_error / static_cast<double>(target.V.rows()), 0.02 * extent);
    // A correspondence file of another template is refused, naming it.
    const TriangleMesh small_limb = make_limb(2);
    VertexAttributes small;
    small.scalars.emplace_back("v", Eigen::VectorXd::Zero(small_limb.V.rows()));
    write_mesh(directory / "small.ply", small_limb, small);
    const auto mismatch = run_genflow(
        "transfer " + quoted(directory / "small.ply") + " " + quoted(directory / "target.ply") +
        " " + quoted(directory / "map.txt") + " -o " + quoted(directory / "x.ply"));
    EXPECT_EQ(mismatch.exit_code, 2);
    EXPECT_NE(mismatch.err.find("map.txt: line"), std::string::npos) << mismatch.err;
    EXPECT_FALSE(std::filesystem::exists(directory / "x.ply"));
}

// The counterparts' stage runs by default (and says how many vertices it moved from the closest
// point), --no-counterparts turns it off, and --counterpart-reach must be positive.
// Every output is checked before the match: one that cannot be written fails the run (exit 1)
// and leaves the others as they were, an existing output untouched.
TEST(MatchCli, AnUnwritableOutputFailsTheRunBeforeAnyWorkAndChangesNothing) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "template.ply", make_limb(2));
    write_mesh(directory / "target.ply", make_limb(2, 5));
    test::write_bytes(directory / "p.ply", "old");
    const std::string command = "match " + quoted(directory / "template.ply") + " " +
                                quoted(directory / "target.ply") + " -o " +
                                quoted(directory / "p.ply");
    for (const auto& [flags, says] :
         {std::pair{" --summary " + quoted(directory / "nodir" / "s.json"),
                    "s.json: cannot be written: the directory"},
          {" --correspondence " + quoted(directory.path()), ": is a directory"}}) {
        const auto result = run_genflow(command + flags);
        EXPECT_EQ(result.exit_code, 1) << result.err;
        EXPECT_NE(result.err.find(says), std::string::npos) << result.err;
        EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    }
    const auto missing = run_genflow("match " + quoted(directory / "template.ply") + " " +
                                     quoted(directory / "target.ply") + " -o " +
                                     quoted(directory / "nodir" / "x.ply"));
    EXPECT_EQ(missing.exit_code, 1) << missing.err;
    EXPECT_EQ(read_file(directory / "p.ply"), "old");
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(directory.path()),
                            std::filesystem::directory_iterator()),
              3);
}

// Part labels and part weights say the same thing two ways: one of them, and only with a part
// tree (without one they were ignored silently).
TEST(MatchCli, PartOptionsGoTogether) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "template.ply", make_limb(2));
    const std::string command = "match " + quoted(directory / "template.ply") + " " +
                                quoted(directory / "template.ply") + " -o " +
                                quoted(directory / "out.ply");
    for (const auto& [flags, says] :
         {std::pair{" --parts p.json --part-labels l.txt --part-weights w.txt",
                    "--part-labels excludes --part-weights"},
          {" --part-labels l.txt", "--part-labels requires --parts"},
          {" --parts-pose 1", "--parts-pose requires --parts"}}) {
        const auto result = run_genflow(command + flags);
        EXPECT_EQ(result.exit_code, 2) << flags;
        EXPECT_NE(result.err.find(says), std::string::npos) << result.err;
        EXPECT_FALSE(std::filesystem::exists(directory / "out.ply"));
    }
}

TEST(MatchCli, CounterpartsHaveTheirSwitchAndReach) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "template.ply", make_limb(3));
    write_mesh(directory / "target.ply", make_limb(4, 5));
    const std::string command =
        "match " + quoted(directory / "template.ply") + " " + quoted(directory / "target.ply") +
        " -o " + quoted(directory / "out.ply") + " --prior rigid --iterations 30 --json";
    const auto on = run_genflow(command + " --counterpart-reach 0.1");
    ASSERT_EQ(on.exit_code, 0) << on.err;
    EXPECT_GE(nlohmann::json::parse(on.out)["counterparts_moved"].get<long>(), 0);
    const auto off = run_genflow(command + " --no-counterparts");
    ASSERT_EQ(off.exit_code, 0) << off.err;
    EXPECT_TRUE(nlohmann::json::parse(off.out)["counterparts_moved"].is_null());
    const auto refused = run_genflow(command + " --counterpart-reach 0");
    EXPECT_NE(refused.exit_code, 0);
    EXPECT_NE(refused.err.find("--counterpart-reach"), std::string::npos) << refused.err;
}

// --stagnation-tolerance reaches the flows: a loose one stops the coarsest level's flow sooner.
TEST(MatchCli, StagnationToleranceStopsTheFlowSooner) {
    const test::TemporaryDirectory directory;
    TriangleMesh target = make_limb(4, 5);
    target.V.col(0) *= 1.1;  // a stretch the rigid prior cannot follow, so its flow creeps on
    write_mesh(directory / "template.ply", make_limb(3));
    write_mesh(directory / "target.ply", target);
    const std::string command =
        "match " + quoted(directory / "template.ply") + " " + quoted(directory / "target.ply") +
        " -o " + quoted(directory / "out.ply") + " --prior rigid --iterations 200 --json";
    const auto coarsest_steps = [&](const std::string& extra) {
        const auto result = run_genflow(command + extra);
        EXPECT_EQ(result.exit_code, 0) << result.err;
        return result.exit_code == 0
                   ? nlohmann::json::parse(result.out)["levels"].back()["iterations"].get<int>()
                   : -1;
    };
    const int by_default = coarsest_steps("");
    const int loose = coarsest_steps(" --stagnation-tolerance 0.05");
    std::printf("coarsest level: %d steps by default, %d at 0.05\n", by_default, loose);
    EXPECT_GE(loose, 20);  // the stagnation window
    EXPECT_LT(loose, by_default);
    const auto refused = run_genflow(command + " --stagnation-tolerance -1");
    EXPECT_NE(refused.exit_code, 0);
    EXPECT_NE(refused.err.find("--stagnation-tolerance"), std::string::npos) << refused.err;
}

TEST(MatchCli, RunsTheIsometricPriorWithItsOptionsAndImplicitSteps) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "template.ply", make_limb(2));
    write_mesh(directory / "target.ply", make_limb(3, 4));
    const std::string command = "match " + quoted(directory / "template.ply") + " " +
                                quoted(directory / "target.ply") + " -o " +
                                quoted(directory / "out.ply") + " --prior isometric --no-align";
    const auto result = run_genflow(
        command +
        " --rigidity-length 0.3 --fake-edges 20 --implicit --no-turn-back --no-limb-swaps"
        " --no-signature-fallback"
        " --map-fits 0 --json");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto json = nlohmann::json::parse(result.out);
    EXPECT_EQ(json["prior"], "isometric");
    EXPECT_LT(json["mean_distance_over_diagonal"].get<double>(), 0.01);
    for (const char* refused_option : {" --rigidity-length -1", " --map-fits -1"}) {
        EXPECT_NE(run_genflow(command + refused_option).exit_code, 0) << refused_option;
    }
    for (const std::string option : {"--second-opinion-above", "--alternative-starts-above"}) {
        for (const std::string threshold : {"-0.1", "nan", "x"}) {
            const auto no_threshold = run_genflow(command + " " + option + " " + threshold);
            EXPECT_NE(no_threshold.exit_code, 0) << option << " " << threshold;
            EXPECT_NE(no_threshold.err.find(option), std::string::npos) << no_threshold.err;
        }
    }
    // inf, never, is a threshold too, for both.
    const auto quiet =
        run_genflow(command + " --quiet --second-opinion-above inf --alternative-starts-above inf");
    ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
    EXPECT_NE(quiet.out.find("isometric prior"), std::string::npos) << quiet.out;
    EXPECT_EQ(quiet.err, "");
}

// --preset paper starts from paper_match_options(); the other flags override it wherever they
// stand on the line.
TEST(MatchCli, PaperPresetTurnsTheStagesOffAndFlagsOverrideIt) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "template.ply", make_limb(3));
    write_mesh(directory / "target.ply", make_limb(3, 5));
    const std::string command = "match " + quoted(directory / "template.ply") + " " +
                                quoted(directory / "target.ply") + " -o " +
                                quoted(directory / "out.ply") + " --json";
    const auto paper = run_genflow(command + " --preset paper");
    ASSERT_EQ(paper.exit_code, 0) << paper.err;
    const auto summary = nlohmann::json::parse(paper.out);
    EXPECT_TRUE(summary["intrinsic_disagreement"].is_null());
    EXPECT_EQ(summary["map_fits"], 0);
    EXPECT_EQ(summary["levels"].size(), 1U);  // automatic: the limb is small
    for (const std::string& line :
         {command + " --levels 2 --preset paper", command + " --preset paper --levels 2"}) {
        const auto two_levels = run_genflow(line);
        ASSERT_EQ(two_levels.exit_code, 0) << two_levels.err;
        EXPECT_EQ(nlohmann::json::parse(two_levels.out)["levels"].size(), 2U) << line;
    }
    const auto unknown = run_genflow(command + " --preset fast");
    EXPECT_NE(unknown.exit_code, 0);
    EXPECT_NE(unknown.err.find("--preset"), std::string::npos) << unknown.err;
}

// A template that is not manifold (a fin on an edge, a face written twice) is matched as
// repaired, with a warning; the output keeps all its vertices and faces.
TEST(MatchCli, MatchesANonManifoldTemplateAsRepaired) {
    const test::TemporaryDirectory directory;
    TriangleMesh fin = make_limb(2);
    const Eigen::Index n = fin.V.rows();
    const Eigen::Index faces = fin.F.rows();
    fin.V.conservativeResize(n + 1, 3);
    fin.V.row(n) = 2 * fin.V.row(fin.F(0, 0));
    fin.F.conservativeResize(faces + 2, 3);
    fin.F.row(faces) << fin.F(0, 0), fin.F(0, 1), static_cast<int>(n);
    fin.F.row(faces + 1) << fin.F(0, 0), fin.F(0, 2), fin.F(0, 1);
    write_mesh(directory / "fin.obj", fin);
    write_mesh(directory / "limb.ply", make_limb(3, 5));
    const auto out = directory / "out.ply";
    // Its own positions as the ground truth: the stages' errors are how far it moved, each
    // repaired vertex measured against the input vertex it stands for.
    const auto result = run_genflow("match " + quoted(directory / "fin.obj") + " " +
                                    quoted(directory / "limb.ply") + " -o " + quoted(out) +
                                    " --prior rigid --iterations 30 --json --ground-truth " +
                                    quoted(directory / "fin.obj"));
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto json = nlohmann::json::parse(result.out);
    ASSERT_FALSE(json["stages"].empty());
    const double moved = json["correspondence_error_over_diagonal"]["mean"].get<double>();
    EXPECT_GT(moved, 0.01);
    EXPECT_NEAR(json["stages"].back()["mean"].get<double>(), moved, 0.2 * moved);
    EXPECT_TRUE(json["template_repairs"].get<std::string>().starts_with(
        "removed duplicate faces: 1; split non-manifold vertices: 2; left out 1 smaller "
        "components"))
        << json["template_repairs"];
    const TriangleMesh matched = read_mesh(out);
    EXPECT_EQ(matched.V.rows(), fin.V.rows());
    EXPECT_EQ(matched.F, fin.F);
    // As a target too.
    const auto as_target = run_genflow("match " + quoted(directory / "limb.ply") + " " +
                                       quoted(directory / "fin.obj") + " -o " + quoted(out) +
                                       " --prior rigid --iterations 30");
    ASSERT_EQ(as_target.exit_code, 0) << as_target.err;
    EXPECT_NE(as_target.err.find("fin.obj: matched as repaired"), std::string::npos)
        << as_target.err;
}

// Landmarks from a file ('i x y z' and 'i j' lines) hold their vertices and are reported; a
// bad line is refused with the file and the line named, before anything is matched or written.
TEST(MatchCli, TakesLandmarksAndRefusesABadFileWritingNothing) {
    const test::TemporaryDirectory directory;
    const TriangleMesh limb = make_limb(3);
    Similarity turn;
    turn.rotation = Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const TriangleMesh target{turn.apply(limb.V), limb.F};
    write_mesh(directory / "template.ply", limb);
    write_mesh(directory / "target.ply", target);
    {
        std::ofstream marks(directory / "marks.txt");
        marks << "# template vertex, then its place\n";
        for (const Eigen::Index v : {Eigen::Index{0}, limb.V.rows() / 3, 2 * limb.V.rows() / 3}) {
            marks << v << ' ' << target.V(v, 0) << ' ' << target.V(v, 1) << ' ' << target.V(v, 2)
                  << '\n';
        }
        marks << limb.V.rows() - 1 << ' ' << limb.V.rows() - 1 << "  # a target vertex\n";
        std::ofstream(directory / "bad.txt") << "0 0\n1 2 x 3\n";
    }
    const auto out = directory / "out.ply";
    const std::string command = "match " + quoted(directory / "template.ply") + " " +
                                quoted(directory / "target.ply") + " -o " + quoted(out) +
                                " --preset paper --levels 2 --json --landmarks ";
    const auto result = run_genflow(command + quoted(directory / "marks.txt"));
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto summary = nlohmann::json::parse(result.out);
    EXPECT_EQ(summary["landmarks"], 4);
    EXPECT_LT(summary["landmark_distance_over_diagonal"].get<double>(), 0.005);
    std::filesystem::remove(out);
    const auto bad = run_genflow(command + quoted(directory / "bad.txt"));
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("bad.txt: line 2: expected a finite coordinate, got 'x'"),
              std::string::npos)
        << bad.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    const auto negative =
        run_genflow(command + quoted(directory / "marks.txt") + " --landmark-weight -1");
    EXPECT_EQ(negative.exit_code, 2);
    EXPECT_NE(negative.err.find("--landmark-weight"), std::string::npos) << negative.err;
}

// An .xyz file, or a mesh file without faces, is a point cloud target: matched on a surface
// made on its points (with their normals where an XYZ or PLY gives them), reported in the
// summary; a bad one is refused before anything is written.
TEST(MatchCli, TakesAPointCloudTargetAndRefusesABadOneWritingNothing) {
    const test::TemporaryDirectory directory;
    const TriangleMesh limb = make_limb(3);
    Similarity turn;
    turn.rotation = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const TriangleMesh sampled = make_limb(3, 5);
    const Eigen::MatrixX3d points = turn.apply(sampled.V);
    const Eigen::MatrixX3d normals = vertex_normals(sampled) * turn.rotation.transpose();
    write_mesh(directory / "template.ply", limb);
    {
        std::ofstream xyz(directory / "scan.xyz");
        xyz << "# x y z nx ny nz\n";
        for (Eigen::Index i = 0; i < points.rows(); ++i) {
            xyz << points.row(i) << ' ' << normals.row(i) << '\n';
        }
        std::ofstream ply(directory / "scan.ply");
        ply << "ply\nformat ascii 1.0\nelement vertex " << points.rows()
            << "\nproperty double x\nproperty double y\nproperty double z\n"
               "property double nx\nproperty double ny\nproperty double nz\nend_header\n";
        for (Eigen::Index i = 0; i < points.rows(); ++i) {
            ply << points.row(i) << ' ' << normals.row(i) << '\n';
        }
        std::ofstream bare(directory / "bare.xyz");
        for (Eigen::Index i = 0; i < points.rows(); ++i) {
            bare << points.row(i) << '\n';
        }
        std::ofstream(directory / "bad.xyz") << "0 0 0\n1 2\n";
        std::ofstream(directory / "three.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    }
    const auto out = directory / "out.ply";
    const std::string command = "match " + quoted(directory / "template.ply") + " ";
    const std::string flags = " -o " + quoted(out) + " --preset paper --levels 2";
    const auto result = run_genflow(command + quoted(directory / "scan.xyz") + flags + " --json");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto summary = nlohmann::json::parse(result.out);
    EXPECT_EQ(summary["target_points"], points.rows());
    EXPECT_TRUE(summary["target_normals"].get<bool>());
    EXPECT_LT(summary["mean_distance_over_diagonal"].get<double>(), 0.01);
    EXPECT_EQ(read_mesh(out).V.rows(), limb.V.rows());
    std::filesystem::remove(out);
    // A PLY's vertex normals are the points' normals, as a scanner exports them.
    const auto ply = run_genflow(command + quoted(directory / "scan.ply") + flags + " --json");
    ASSERT_EQ(ply.exit_code, 0) << ply.err;
    EXPECT_TRUE(nlohmann::json::parse(ply.out)["target_normals"].get<bool>());
    std::filesystem::remove(out);
    // Without normals it matches too, and says what normals would settle.
    const auto bare = run_genflow(command + quoted(directory / "bare.xyz") + flags);
    ASSERT_EQ(bare.exit_code, 0) << bare.err;
    EXPECT_NE(bare.err.find("bare.xyz: no normals"), std::string::npos) << bare.err;
    std::filesystem::remove(out);
    for (const auto& [file, says] :
         {std::pair{"bad.xyz", "bad.xyz: line 2: expected 'x y z'"},
          {"three.obj", "three.obj: a point cloud, but 3 points; at least 4 are needed"}}) {
        const auto bad = run_genflow(command + quoted(directory / file) + flags);
        EXPECT_EQ(bad.exit_code, 2);
        EXPECT_NE(bad.err.find(says), std::string::npos) << bad.err;
        EXPECT_FALSE(std::filesystem::exists(out));
    }
}

// One side of the limb is found partial and matched as such, unless the target's extent is
// given; a bad extent is refused with the option named, and nothing written.
TEST(MatchCli, MatchesAViewAsAPartialTargetUnlessToldOtherwise) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "template.ply", make_limb(3));
    write_mesh(directory / "view.ply", single_view(make_limb(3, 5), Eigen::Vector3d(0.2, 0.3, -1)));
    const auto out = directory / "out.ply";
    const std::string command = "match " + quoted(directory / "template.ply") + " " +
                                quoted(directory / "view.ply") + " -o " + quoted(out) +
                                " --preset paper --levels 1 --iterations 20 --json";
    for (const auto& [extent, partial] : {std::pair{"", true},
                                          {" --target-extent partial", true},
                                          {" --target-extent complete", false}}) {
        const auto result = run_genflow(command + extent);
        ASSERT_EQ(result.exit_code, 0) << result.err;
        EXPECT_EQ(nlohmann::json::parse(result.out)["partial_target"].get<bool>(), partial)
            << extent;
    }
    std::filesystem::remove(out);
    const auto bad = run_genflow(command + " --target-extent half");
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("--target-extent"), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(MatchCli, RefusesBadInputAndWritesNothing) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "limb.ply", make_limb(2));
    {
        std::ofstream nan(directory / "nan.obj");
        nan << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
        std::ofstream empty(directory / "empty.obj");
    }
    const auto out = directory / "out.ply";
    for (const char* bad : {"nan.obj", "empty.obj", "missing.ply"}) {
        const auto as_target = run_genflow("match " + quoted(directory / "limb.ply") + " " +
                                           quoted(directory / bad) + " -o " + quoted(out));
        EXPECT_EQ(as_target.exit_code, 2) << bad;
        EXPECT_NE(as_target.err.find(bad), std::string::npos) << as_target.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << bad;
    }
    // A ground truth that does not fit the template: refused before the match.
    write_mesh(directory / "small.ply", make_limb(1));
    const auto wrong_truth = run_genflow("match " + quoted(directory / "limb.ply") + " " +
                                         quoted(directory / "limb.ply") + " -o " + quoted(out) +
                                         " --ground-truth " + quoted(directory / "small.ply"));
    EXPECT_EQ(wrong_truth.exit_code, 2);
    EXPECT_NE(wrong_truth.err.find("small.ply: the ground truth has"), std::string::npos)
        << wrong_truth.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    // A pose the part file does not have.
    {
        std::ofstream(directory / "parts.json")
            << R"({"parts": [{"name": "limb", "parent": null, "joint_center": [0, 0, 0]}],
                   "labels": "labels.txt"})";
        std::ofstream labels(directory / "labels.txt");
        for (Eigen::Index v = 0; v < make_limb(2).V.rows(); ++v) {
            labels << "0\n";
        }
    }
    const auto no_pose = run_genflow(
        "match " + quoted(directory / "limb.ply") + " " + quoted(directory / "limb.ply") + " -o " +
        quoted(out) + " --parts " + quoted(directory / "parts.json") + " --parts-pose pose1");
    EXPECT_EQ(no_pose.exit_code, 2);
    EXPECT_NE(no_pose.err.find("parts.json: has no poses"), std::string::npos) << no_pose.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    const auto unknown_prior =
        run_genflow("match " + quoted(directory / "limb.ply") + " " +
                    quoted(directory / "limb.ply") + " -o " + quoted(out) + " --prior banana");
    EXPECT_EQ(unknown_prior.exit_code, 2);
    // Two step rules at once: one line naming both options.
    const auto two_steps = run_genflow("match " + quoted(directory / "limb.ply") + " " +
                                       quoted(directory / "limb.ply") + " -o " + quoted(out) +
                                       " --implicit --quasi-newton 5");
    EXPECT_EQ(two_steps.exit_code, 2);
    EXPECT_NE(two_steps.err.find("--quasi-newton"), std::string::npos) << two_steps.err;
    EXPECT_NE(two_steps.err.find("--implicit"), std::string::npos) << two_steps.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    const auto unknown_first_step = run_genflow("match " + quoted(directory / "limb.ply") + " " +
                                                quoted(directory / "limb.ply") + " -o " +
                                                quoted(out) + " --first-step halving");
    EXPECT_EQ(unknown_first_step.exit_code, 2);
    EXPECT_NE(unknown_first_step.err.find("--first-step"), std::string::npos)
        << unknown_first_step.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace genflow
