// SPDX-License-Identifier: MIT
#include "genflow/io/write_mesh.h"

#include <gtest/gtest.h>

#include <limits>

#include "genflow/exceptions.h"
#include "genflow/io/read_mesh.h"
#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

class RoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(RoundTrip, IsExactForDoublePrecisionFormats) {
    const test::TemporaryDirectory directory;
    const TriangleMesh mesh = test::noisy_torus(9, 5, 0.3, 11);
    const auto path = directory / ("mesh." + GetParam());
    write_mesh(path, mesh);
    const TriangleMesh back = read_mesh(path);
    EXPECT_EQ(back.V, mesh.V);  // bitwise: shortest round-trip text or raw doubles
    EXPECT_EQ(back.F, mesh.F);
}

INSTANTIATE_TEST_SUITE_P(Formats, RoundTrip, ::testing::Values("obj", "ply", "off", "OBJ"));

TEST(WriteMesh, AsciiAndFloatPly) {
    const test::TemporaryDirectory directory;
    const TriangleMesh mesh = test::noisy_icosphere(1, 0.3);
    for (const auto encoding : {PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian}) {
        write_mesh(directory / "d.ply", mesh, {.ply_encoding = encoding});
        EXPECT_EQ(read_mesh(directory / "d.ply").V, mesh.V);
        write_mesh(directory / "f.ply", mesh,
                   {.ply_encoding = encoding, .ply_precision = PlyPrecision::Float});
        const TriangleMesh back = read_mesh(directory / "f.ply");
        EXPECT_EQ(back.F, mesh.F);
        EXPECT_EQ(back.V, mesh.V.cast<float>().cast<double>());
    }
}

TEST(WriteMesh, FailureLeavesNoFileAndKeepsTheOldOne) {
    const test::TemporaryDirectory directory;
    const TriangleMesh mesh = make_icosphere(1);
    EXPECT_THROW(write_mesh(directory / "missing-dir" / "out.ply", mesh), IoError);
    EXPECT_TRUE(std::filesystem::is_empty(directory.path()));

    const auto path = directory / "out.off";
    write_mesh(path, mesh);
    TriangleMesh broken = mesh;
    broken.F(0, 0) = 1000;
    EXPECT_THROW(write_mesh(path, broken), InvalidInput);
    EXPECT_EQ(read_mesh(path).F, mesh.F);  // the previous file is intact
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(directory.path()),
                            std::filesystem::directory_iterator()),
              1);
}

TEST(WriteMesh, ParentThatIsAFileGivesIoErrorWithThePath) {
    const test::TemporaryDirectory directory;
    test::write_bytes(directory / "file", "x");
    try {
        write_mesh(directory / "file" / "out.ply", make_icosphere(0));
        FAIL() << "expected IoError";
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()).rfind((directory / "file" / "out.ply").string() + ": ", 0),
                  0u)
            << e.what();
    }
}

TEST(WriteMesh, RejectsUnknownOrStlExtensions) {
    const test::TemporaryDirectory directory;
    EXPECT_THROW(write_mesh(directory / "out.xyz", make_icosphere(0)), IoError);
    EXPECT_THROW(write_mesh(directory / "out.stl", make_icosphere(0)), IoError);
    EXPECT_TRUE(std::filesystem::is_empty(directory.path()));
}

// A result with a NaN or an infinity is not written: no reader would take the file back.
TEST(WriteMesh, RefusesNonFiniteCoordinatesAndWritesNothing) {
    const test::TemporaryDirectory directory;
    for (const double bad :
         {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        TriangleMesh mesh = make_icosphere(0);
        mesh.V(3, 1) = bad;
        for (const char* name : {"out.ply", "out.obj", "out.off"}) {
            EXPECT_THROW(write_mesh(directory / name, mesh), InvalidInput) << name;
        }
    }
    EXPECT_TRUE(std::filesystem::is_empty(directory.path()));
}

}  // namespace
}  // namespace genflow
