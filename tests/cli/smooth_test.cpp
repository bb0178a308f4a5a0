// SPDX-License-Identifier: MIT
// genflow smooth end to end, on generated meshes.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.h"
#include "genflow/io/read_file.h"
#include "genflow/io/read_mesh.h"
#include "genflow/io/write_mesh.h"
#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

using test::quoted;
using test::run_genflow;

TEST(SmoothCli, EveryMethodWritesASmootherMeshAndAJsonSummary) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "noisy.ply", test::noisy_icosphere(3, 0.2));
    for (const char* method : {"mcf", "fairing", "fairing2", "volume-fairing"}) {
        const auto out = directory / (std::string(method) + ".off");
        const auto result = run_genflow("smooth " + quoted(directory / "noisy.ply") + " " +
                                        quoted(out) + " --method " + method + " --steps 3 --json");
        ASSERT_EQ(result.exit_code, 0) << method << ": " << result.err;
        const auto json = nlohmann::json::parse(result.out);
        EXPECT_EQ(json["method"], method);
        EXPECT_EQ(json["steps"], 3);
        EXPECT_EQ(json["status"], "max-steps");
        EXPECT_EQ(json["energy"].size(), 4u);
        EXPECT_LT(json["area_after"].get<double>(), json["area_before"].get<double>());
        EXPECT_FALSE(json["energy_rose"].get<bool>());
        EXPECT_EQ(read_mesh(out).F.rows(), 1280);
    }
}

// A flow whose time step is too large for its metric (fairing with a tiny λ is nearly explicit)
// makes the area grow: it says so, in a warning and in the JSON, instead of reporting success.
TEST(SmoothCli, SaysSoWhenTheEnergyRose) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "noisy.ply", test::noisy_icosphere(3, 0.2));
    const std::string command = "smooth " + quoted(directory / "noisy.ply") + " " +
                                quoted(directory / "out.ply") +
                                " --method fairing --lambda 0.001 --dt 3";
    const auto text = run_genflow(command);
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.err.find("the flow's energy rose"), std::string::npos) << text.err;
    const auto json = nlohmann::json::parse(run_genflow(command + " --json").out);
    EXPECT_TRUE(json["energy_rose"].get<bool>());
    EXPECT_GT(json["area_after"].get<double>(), json["area_before"].get<double>());
}

// What the input gives per vertex goes with its vertices: colours and values are written with
// the smoothed mesh; its normals, which described the surface before, are left out and it
// says so.
TEST(SmoothCli, CarriesTheInputsColoursAndValuesAndSaysWhatItLeavesOut) {
    const test::TemporaryDirectory directory;
    const TriangleMesh noisy = test::noisy_icosphere(3, 0.2);
    VertexAttributes attributes;
    attributes.normals = noisy.V;
    attributes.colors = VertexColors::Zero(noisy.V.rows(), 3);
    attributes.colors.col(0) = (noisy.V.col(0).array() > 0).cast<std::uint8_t>() * 255;
    attributes.scalars.emplace_back("quality", noisy.V.col(1));
    attributes.uvs = noisy.V.leftCols(2);
    write_mesh(directory / "in.ply", noisy, attributes);
    const auto result = run_genflow("smooth " + quoted(directory / "in.ply") + " " +
                                    quoted(directory / "out.ply") + " --steps 2");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.err.find("in.ply: its vertex normals are left out"), std::string::npos)
        << result.err;
    VertexAttributes out;
    const TriangleMesh smoothed = read_mesh(directory / "out.ply", nullptr, &out);
    EXPECT_GT((smoothed.V - noisy.V).norm(), 0);
    EXPECT_EQ(out.colors, attributes.colors);
    ASSERT_EQ(out.scalars.size(), 1U);
    EXPECT_EQ(out.scalars[0].second, attributes.scalars[0].second);
    EXPECT_EQ(out.normals.rows(), 0);
    EXPECT_EQ(out.uvs, attributes.uvs);
    // info says what the file gives per vertex.
    const auto info =
        nlohmann::json::parse(run_genflow("info --json " + quoted(directory / "in.ply")).out);
    EXPECT_EQ(info["vertex_attributes"], nlohmann::json({{"normals", true},
                                                         {"colors", true},
                                                         {"values", {"quality"}},
                                                         {"texture_coordinates", "per vertex"}}));
    // OFF keeps the colours, not the values: said too.
    const auto off = run_genflow("smooth " + quoted(directory / "in.ply") + " " +
                                 quoted(directory / "out.off") + " --steps 2");
    ASSERT_EQ(off.exit_code, 0) << off.err;
    EXPECT_NE(off.err.find("out.off: .off holds no vertex values;"), std::string::npos) << off.err;
}

TEST(SmoothCli, VolumeFairingKeepsTheVolumeThatFairingLoses) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "noisy.ply", test::noisy_torus(60, 24, 0.3));
    const auto run = [&](const std::string& method) {
        const auto result = run_genflow("smooth " + quoted(directory / "noisy.ply") + " " +
                                        quoted(directory / "out.ply") +
                                        " --json --dt 2 --steps 4 --method " + method);
        EXPECT_EQ(result.exit_code, 0) << result.err;
        return nlohmann::json::parse(result.out)["volume_change_percent"].get<double>();
    };
    const double plain = run("fairing");
    const double controlled = run("volume-fairing");
    EXPECT_LT(plain, -1.0);
    EXPECT_LT(std::abs(controlled), 0.2 * std::abs(plain));
}

TEST(SmoothCli, FramesAndTextSummary) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "noisy.obj", test::noisy_icosphere(2, 0.2));
    const auto result =
        run_genflow("smooth " + quoted(directory / "noisy.obj") + " " +
                    quoted(directory / "out.ply") + " --method fairing --steps 4 --frames " +
                    quoted(directory / "frames") + " --frame-every 2");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("smooth: fairing, 4 steps"), std::string::npos) << result.out;
    for (const char* frame : {"frame_00000.ply", "frame_00002.ply", "frame_00004.ply"}) {
        EXPECT_TRUE(std::filesystem::exists(directory / "frames" / frame)) << frame;
    }
    EXPECT_FALSE(std::filesystem::exists(directory / "frames" / "frame_00001.ply"));
    // The same frames as one animated glTF: frame 0 the mesh, the other two its morph targets.
    const auto animated =
        run_genflow("smooth " + quoted(directory / "noisy.obj") + " " +
                    quoted(directory / "out.ply") + " --method fairing --steps 4 --frames " +
                    quoted(directory / "frames.glb") + " --frame-every 2");
    ASSERT_EQ(animated.exit_code, 0) << animated.err;
    const std::string glb = read_file(directory / "frames.glb");
    EXPECT_EQ(glb.substr(0, 4), "glTF");
    EXPECT_NE(glb.find("\"targets\""), std::string::npos);
    EXPECT_NE(glb.find("\"animations\""), std::string::npos);
    EXPECT_NE(glb.find("\"weights\":[0.0,0.0]"), std::string::npos);
}

TEST(SmoothCli, BadArgumentsAndInputsAreRefusedWithoutOutput) {
    const test::TemporaryDirectory directory;
    write_mesh(directory / "in.ply", make_icosphere(2));
    test::write_bytes(directory / "nan.off", "OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    const std::vector<std::string> bad = {
        "smooth " + quoted(directory / "in.ply") + " " + quoted(directory / "out.ply") +
            " --method nope",
        "smooth " + quoted(directory / "in.ply") + " " + quoted(directory / "out.ply") + " --dt -1",
        "smooth " + quoted(directory / "in.ply") + " " + quoted(directory / "out.ply") +
            " --volume-lambda 2",
        "smooth " + quoted(directory / "in.ply") + " " + quoted(directory / "out.vtk"),
        "smooth " + quoted(directory / "nan.off") + " " + quoted(directory / "out.ply"),
        "smooth " + quoted(directory / "missing.ply") + " " + quoted(directory / "out.ply"),
    };
    for (const auto& arguments : bad) {
        const auto result = run_genflow(arguments);
        EXPECT_EQ(result.exit_code, 2) << arguments << ": " << result.err;
        EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
        EXPECT_FALSE(std::filesystem::exists(directory / "out.ply"));
        EXPECT_FALSE(std::filesystem::exists(directory / "out.vtk"));
    }
}

}  // namespace
}  // namespace genflow
