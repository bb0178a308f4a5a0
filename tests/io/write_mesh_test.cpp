// SPDX-License-Identifier: MIT
#include "genflow/io/write_mesh.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <limits>

#include "genflow/exceptions.h"
#include "genflow/io/read_file.h"
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

TEST(WriteMesh, RejectsUnknownExtensions) {
    const test::TemporaryDirectory directory;
    EXPECT_THROW(write_mesh(directory / "out.xyz", make_icosphere(0)), IoError);
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

// Colours and named values are written where the format holds them, and what genflow writes
// it reads back: the same positions and faces in every format.
TEST(WriteMesh, WritesVertexColoursAndValuesThatItReadsBack) {
    const test::TemporaryDirectory directory;
    const TriangleMesh mesh = make_icosphere(1);
    VertexAttributes attributes;
    attributes.colors = VertexColors::Zero(mesh.V.rows(), 3);
    attributes.colors.col(0).setConstant(255);
    attributes.colors(0, 1) = 7;
    attributes.scalars.emplace_back("distance", mesh.V.col(0).array().abs());
    for (const char* name : {"out.ply", "ascii.ply", "out.obj", "out.off"}) {
        std::vector<std::string> warnings;
        const WriteMeshOptions options{.ply_encoding = std::string(name) == "ascii.ply"
                                                           ? PlyEncoding::Ascii
                                                           : PlyEncoding::BinaryLittleEndian};
        write_mesh(directory / name, mesh, attributes, options, &warnings);
        const TriangleMesh back = read_mesh(directory / name);
        EXPECT_EQ(back.V, mesh.V) << name;
        EXPECT_EQ(back.F, mesh.F) << name;
        EXPECT_EQ(warnings.size(), std::string(name).ends_with(".ply") ? 0U : 1U) << name;
    }
    const std::string ascii = read_file(directory / "ascii.ply");
    EXPECT_NE(ascii.find("property double distance\nproperty uchar red\n"), std::string::npos);
    // Vertex 0's row ends with its colour.
    const std::string first_row = ascii.substr(ascii.find("end_header\n") + 11);
    EXPECT_NE(first_row.substr(0, first_row.find('\n')).find(" 255 7 0"), std::string::npos)
        << first_row.substr(0, first_row.find('\n'));
    EXPECT_NE(read_file(directory / "out.off").find("COFF\n"), std::string::npos);
    EXPECT_NE(read_file(directory / "out.obj").find(" 1 0.027450980392156862 0\n"),
              std::string::npos);
}

// Binary STL: what the STL reader reads back is the mesh, to float precision.
TEST(WriteMesh, WritesBinaryStl) {
    const test::TemporaryDirectory directory;
    const TriangleMesh mesh = make_icosphere(2);
    VertexAttributes attributes;
    attributes.scalars.emplace_back("d", Eigen::VectorXd::Zero(mesh.V.rows()));
    std::vector<std::string> warnings;
    write_mesh(directory / "out.stl", mesh, attributes, {}, &warnings);
    EXPECT_EQ(warnings.size(), 1U);  // the values are left out
    EXPECT_EQ(std::filesystem::file_size(directory / "out.stl"), 84 + 50 * mesh.F.rows());
    const TriangleMesh back = read_mesh(directory / "out.stl");
    ASSERT_EQ(back.V.rows(), mesh.V.rows());  // corners welded back into vertices
    ASSERT_EQ(back.F.rows(), mesh.F.rows());
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_LT((back.V.row(back.F(f, c)) - mesh.V.row(mesh.F(f, c))).norm(), 1e-7);
        }
    }
}

// Binary glTF, read back by TinyGLTF as a viewer would: the positions and faces, a unit normal
// per vertex, the colours (linear, as glTF has them) and the values as "_NAME" attributes.
TEST(WriteMesh, WritesBinaryGltfThatTinyGltfReadsBack) {
    const test::TemporaryDirectory directory;
    const TriangleMesh mesh = make_icosphere(1);
    VertexAttributes attributes;
    attributes.colors = VertexColors::Constant(mesh.V.rows(), 3, 255);
    attributes.colors(2, 0) = 0;
    attributes.colors(2, 1) = 188;  // sRGB 188 is linear 0.5029
    attributes.scalars.emplace_back("distance", Eigen::VectorXd::LinSpaced(mesh.V.rows(), 0, 1));
    attributes.uvs = mesh.V.leftCols(2);
    write_mesh(directory / "out.GLB", mesh, attributes);
    const std::string bytes = read_file(directory / "out.GLB");
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error;
    std::string warning;
    ASSERT_TRUE(loader.LoadBinaryFromMemory(&model, &error, &warning,
                                            reinterpret_cast<const unsigned char*>(bytes.data()),
                                            static_cast<unsigned>(bytes.size())))
        << error;
    ASSERT_EQ(model.meshes.size(), 1U);
    const tinygltf::Primitive& primitive = model.meshes[0].primitives.at(0);
    const auto floats = [&](const char* attribute) {
        const tinygltf::Accessor& accessor =
            model.accessors.at(static_cast<std::size_t>(primitive.attributes.at(attribute)));
        const tinygltf::BufferView& view =
            model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
        const auto* data = reinterpret_cast<const float*>(model.buffers.at(0).data.data() +
                                                          view.byteOffset + accessor.byteOffset);
        return std::vector<float>(data, data + view.byteLength / sizeof(float));
    };
    const std::vector<float> positions = floats("POSITION");
    ASSERT_EQ(positions.size(), static_cast<std::size_t>(3 * mesh.V.rows()));
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_FLOAT_EQ(positions[static_cast<std::size_t>(3 * i + c)],
                            static_cast<float>(mesh.V(i, c)));
        }
    }
    const std::vector<float> normals = floats("NORMAL");
    EXPECT_NEAR(normals[0] * normals[0] + normals[1] * normals[1] + normals[2] * normals[2], 1,
                1e-6);
    const std::vector<float> colors = floats("COLOR_0");
    EXPECT_FLOAT_EQ(colors[6], 0);
    EXPECT_NEAR(colors[7], 0.5029, 1e-4);
    EXPECT_FLOAT_EQ(colors[8], 1);
    EXPECT_FLOAT_EQ(floats("_DISTANCE").back(), 1);
    // glTF's v runs down the image, OBJ's and PLY's up.
    const std::vector<float> uvs = floats("TEXCOORD_0");
    ASSERT_EQ(uvs.size(), static_cast<std::size_t>(2 * mesh.V.rows()));
    EXPECT_FLOAT_EQ(uvs[2], static_cast<float>(mesh.V(1, 0)));
    EXPECT_FLOAT_EQ(uvs[3], static_cast<float>(1 - mesh.V(1, 1)));
    const tinygltf::Accessor& indices =
        model.accessors.at(static_cast<std::size_t>(primitive.indices));
    EXPECT_EQ(indices.count, static_cast<std::size_t>(mesh.F.size()));
    EXPECT_TRUE(model.materials.at(0).doubleSided);
}

TEST(WriteMesh, RefusesAttributesThatDoNotFitTheMesh) {
    const test::TemporaryDirectory directory;
    const TriangleMesh mesh = make_icosphere(0);
    VertexAttributes short_colors;
    short_colors.colors = VertexColors::Zero(3, 3);
    VertexAttributes bad_name;
    bad_name.scalars.emplace_back("two words", Eigen::VectorXd::Zero(mesh.V.rows()));
    VertexAttributes short_values;
    short_values.scalars.emplace_back("d", Eigen::VectorXd::Zero(2));
    for (const VertexAttributes* attributes : {&short_colors, &bad_name, &short_values}) {
        EXPECT_THROW(write_mesh(directory / "out.ply", mesh, *attributes), InvalidInput);
    }
    EXPECT_TRUE(std::filesystem::is_empty(directory.path()));
}

}  // namespace
}  // namespace genflow
