// SPDX-License-Identifier: MIT
#include "genflow/io/read_mesh.h"

#include <gtest/gtest.h>

#include <cstring>

#include "genflow/exceptions.h"
#include "genflow/io/write_mesh.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// A unit square as two triangles, the reference for every format below.
TriangleMesh square() {
    TriangleMesh mesh;
    mesh.V.resize(4, 3);
    mesh.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
    mesh.F.resize(2, 3);
    mesh.F << 0, 1, 2, 0, 2, 3;
    return mesh;
}

template <typename T>
std::string bytes_of(T value, bool big_endian) {
    std::string raw(sizeof(T), '\0');
    std::memcpy(raw.data(), &value, sizeof(T));
    if (big_endian) {
        std::reverse(raw.begin(), raw.end());
    }
    return raw;
}

std::string binary_ply(bool big_endian, int declared_vertices = 4) {
    std::string out = "ply\nformat ";
    out += big_endian ? "binary_big_endian" : "binary_little_endian";
    out += " 1.0\ncomment test\nelement vertex " + std::to_string(declared_vertices) +
           "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
           "element face 1\nproperty list uchar uint vertex_indices\n"
           "element extra 2\nproperty short s\nend_header\n";
    const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (const auto& v : xyz) {
        for (float c : v) {
            out += bytes_of(c, big_endian);
        }
        out += '\x7f';  // red
    }
    out += '\x04';  // a quad: split into two triangles
    for (std::uint32_t i : {0u, 1u, 2u, 3u}) {
        out += bytes_of(i, big_endian);
    }
    out += bytes_of(std::int16_t{5}, big_endian) + bytes_of(std::int16_t{6}, big_endian);
    return out;
}

std::string binary_stl(bool lie_about_count = false) {
    std::string out(80, ' ');
    out.replace(0, 5, "solid");  // binary files that start with "solid" exist in the wild
    out += bytes_of(std::uint32_t{lie_about_count ? 3u : 2u}, false);
    const float triangles[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}},
                                      {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
    for (const auto& t : triangles) {
        for (int k = 0; k < 3; ++k) {
            out += bytes_of(0.0f, false);  // normal
        }
        for (const auto& v : t) {
            for (float c : v) {
                out += bytes_of(c, false);
            }
        }
        out += std::string(2, '\0');
    }
    return out;
}

TriangleMesh parse(const std::string& text, MeshFormat format,
                   std::vector<std::string>* warnings = nullptr) {
    return parse_mesh(text, format, "test", warnings);
}

void expect_square(const TriangleMesh& mesh) {
    EXPECT_EQ(mesh.V, square().V);
    EXPECT_EQ(mesh.F, square().F);
}

TEST(ReadMesh, AsciiPly) {
    expect_square(parse(
        "ply\r\nformat ascii 1.0\r\nelement vertex 4\r\nproperty double x\r\nproperty double y\r\n"
        "property double z\r\nelement face 2\r\nproperty list uchar int "
        "vertex_index\r\nend_header\r\n"
        "0 0 0\r\n1 0 0\r\n1 1 0\r\n0 1 0\r\n3 0 1 2\r\n3 0 2 3\r\n",
        MeshFormat::Ply));
}

// A UTF-8 byte order mark before the first line (some Windows editors write one) is not read as
// content: it used to hide the OBJ's first vertex and shift every index by one.
TEST(ReadMesh, TextFilesStartingWithAByteOrderMark) {
    const std::string mark = "\xEF\xBB\xBF";
    expect_square(
        parse(mark + "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n", MeshFormat::Obj));
    expect_square(parse(mark + "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",
                        MeshFormat::Off));
    expect_square(parse(mark + "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\n"
                               "property double y\nproperty double z\nelement face 2\nproperty "
                               "list uchar int vertex_index\nend_header\n"
                               "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",
                        MeshFormat::Ply));
}

TEST(ReadMesh, BinaryPlyInBothByteOrdersWithPolygonsAndExtraElements) {
    for (const bool big : {false, true}) {
        std::vector<std::string> warnings;
        expect_square(parse(binary_ply(big), MeshFormat::Ply, &warnings));
        ASSERT_EQ(warnings.size(), 2u);
        EXPECT_EQ(warnings[0], "test: element 'extra' ignored");
        EXPECT_EQ(warnings[1],
                  "test: 1 polygon(s) with more than 3 corners were split into triangle fans");
    }
}

TEST(ReadMesh, ObjWithPolygonsSlashesNegativeIndicesAndComments) {
    std::vector<std::string> warnings;
    expect_square(
        parse("# comment\nmtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0\n"
              "vn 0 0 1\nvt 0 0\ng square\nf 1/1/1 2//1 3/1 -1 # quad\n",
              MeshFormat::Obj, &warnings));
    EXPECT_EQ(warnings.size(), 1u);  // the quad split; vt and vn are read only when asked for
}

TEST(ReadMesh, OffWithCommentsColoursAndCountsOnTheKeywordLine) {
    expect_square(parse("OFF 4 2 0\n# c\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 255 0 0\n3 0 2 3\n",
                        MeshFormat::Off));
    expect_square(
        parse("COFF\n4 1 5\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n1 1 0 1 1 1 1\n0 1 0 1 1 1 1\n"
              "4 0 1 2 3\n",
              MeshFormat::Off));
}

// The columns the keyword's prefixes announce, in Geomview's order: normals, colour (0–255, or
// 0–1 fractions), texture coordinates; face colours are left out, and said to be.
TEST(ReadMesh, ReadsTheColumnsAnOffKeywordAnnounces) {
    std::vector<std::string> warnings;
    VertexAttributes read;
    const TriangleMesh mesh = parse_mesh(
        "STCNOFF\n3 1 0\n0 0 0 0 0 1 255 0 0 255 0.5 0.25\n1 0 0 0 0 1 0 255 0 255 1 0\n"
        "0 1 0 0 0 1 0 0 255 255 0 1\n3 0 1 2 9 9 9\n",
        MeshFormat::Off, "t.off", &warnings, &read);
    EXPECT_EQ(mesh.F.rows(), 1);
    ASSERT_EQ(read.normals.rows(), 3);
    EXPECT_EQ(read.normals.row(1), Eigen::RowVector3d(0, 0, 1));
    ASSERT_EQ(read.colors.rows(), 3);
    EXPECT_EQ(read.colors(1, 1), 255);
    EXPECT_EQ(read.colors(2, 0), 0);
    ASSERT_EQ(read.uvs.rows(), 3);
    EXPECT_EQ(read.uvs.row(0), Eigen::RowVector2d(0.5, 0.25));
    ASSERT_EQ(warnings.size(), 1U);
    EXPECT_EQ(warnings[0], "t.off: 1 face colours left out");

    (void)parse_mesh("COFF\n3 1 0\n0 0 0 1.0 0.5 0\n1 0 0 1 1 1\n0 1 0 0 0 0\n3 0 1 2\n",
                     MeshFormat::Off, "t.off", nullptr, &read);
    EXPECT_EQ(read.colors(0, 0), 255);  // fractions, written with a point
    EXPECT_EQ(read.colors(0, 1), 128);
    EXPECT_EQ(read.colors(1, 0), 1);  // integers
    EXPECT_THROW((void)parse_mesh("NOFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::Off,
                                  "t.off", nullptr, &read),
                 IoError);

    // Written back with the same columns.
    const test::TemporaryDirectory directory;
    VertexAttributes written = read;
    written.normals = Eigen::MatrixX3d::Ones(3, 3);
    written.uvs = Eigen::MatrixX2d::Constant(3, 2, 0.5);
    write_mesh(directory / "a.off", mesh, written);
    VertexAttributes back;
    (void)read_mesh(directory / "a.off", nullptr, &back);
    EXPECT_EQ(back.normals, written.normals);
    EXPECT_EQ(back.colors, written.colors);
    EXPECT_EQ(back.uvs, written.uvs);
}

TEST(ReadMesh, AsciiStlIsWelded) {
    expect_square(
        parse("solid square\n"
              "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 1 1 0\n"
              " endloop\nendfacet\n"
              "FACET NORMAL 0 0 1\n OUTER LOOP\n  VERTEX 0 0 -0\n  VERTEX 1 1 0\n  VERTEX 0 1 0\n"
              " ENDLOOP\nENDFACET\nendsolid square\n",
              MeshFormat::Stl));
}

TEST(ReadMesh, BinaryStlIsWeldedEvenWhenItStartsWithSolid) {
    std::vector<std::string> warnings;
    expect_square(parse(binary_stl(), MeshFormat::Stl, &warnings));
    EXPECT_TRUE(warnings.empty());
    // A face colour in the attribute bytes, as some writers put it there: left out, and said.
    std::string colored = binary_stl();
    colored[84 + 48] = '\x1f';
    expect_square(parse(colored, MeshFormat::Stl, &warnings));
    ASSERT_EQ(warnings.size(), 1U);
    EXPECT_EQ(warnings[0],
              "test: 1 faces' attribute bytes (face colours of some writers) left out");
}

// A PLY file's vertex normals, colours (uchar, or 0–1 floats as some tools write them) and
// other vertex properties are read when asked for; a lone component is a value of its own.
TEST(ReadMesh, ReadsThePlyVerticesNormalsColoursAndValues) {
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float "
        "quality\nproperty float s\nelement face 1\nproperty list uchar int vertex_indices\n"
        "end_header\n";
    const std::string body =
        "0 0 0 0 0 1 255 0 10 0.5 7\n1 0 0 0 0 1 0 128 0 1.5 8\n"
        "0 1 0 0 0 1 1 2 3 2.5 9\n3 0 1 2\n";
    VertexAttributes attributes;
    const TriangleMesh mesh =
        parse_mesh(header + body, MeshFormat::Ply, "a.ply", nullptr, &attributes);
    ASSERT_EQ(mesh.V.rows(), 3);
    ASSERT_EQ(attributes.normals.rows(), 3);
    EXPECT_EQ(attributes.normals.row(1), Eigen::RowVector3d(0, 0, 1));
    ASSERT_EQ(attributes.colors.rows(), 3);
    EXPECT_EQ(attributes.colors(0, 0), 255);
    EXPECT_EQ(attributes.colors(1, 1), 128);
    EXPECT_EQ(attributes.colors(2, 2), 3);
    ASSERT_EQ(attributes.scalars.size(), 2U);
    EXPECT_EQ(attributes.scalars[0].first, "quality");
    EXPECT_EQ(attributes.scalars[0].second, Eigen::Vector3d(0.5, 1.5, 2.5));
    EXPECT_EQ(attributes.scalars[1].first, "s");
    std::string floats = header;
    for (const char* channel : {"red", "green", "blue"}) {
        floats.replace(floats.find(std::string("uchar ") + channel), 5, "float");
    }
    const std::string float_body =
        "0 0 0 0 0 1 1 0 0.5 0.5 7\n1 0 0 0 0 1 0 1 0 1.5 8\n"
        "0 1 0 0 0 1 0 0 1 2.5 9\n3 0 1 2\n";
    (void)parse_mesh(floats + float_body, MeshFormat::Ply, "f.ply", nullptr, &attributes);
    EXPECT_EQ(attributes.colors(0, 2), 128);  // 0.5 of 255
    std::string lone = header;
    lone.replace(lone.find("property float ny\n"), 18, "");
    const std::string lone_body =
        "0 0 0 0 1 255 0 10 0.5 7\n1 0 0 0 1 0 128 0 1.5 8\n"
        "0 1 0 0 1 1 2 3 2.5 9\n3 0 1 2\n";
    (void)parse_mesh(lone + lone_body, MeshFormat::Ply, "l.ply", nullptr, &attributes);
    EXPECT_EQ(attributes.normals.rows(), 0);
    EXPECT_EQ(attributes.scalars.size(), 4U);  // nx, nz, quality, s
}

// What write_mesh() writes, read_mesh() reads back: PLY keeps normals, colours and values to
// the bit, OBJ the colours.
TEST(ReadMesh, ReadsBackTheAttributesGenflowWrites) {
    const test::TemporaryDirectory directory;
    const TriangleMesh mesh = test::noisy_icosphere(1);
    VertexAttributes written;
    written.normals = mesh.V;
    written.colors = VertexColors::Zero(mesh.V.rows(), 3);
    written.colors.col(1).setConstant(200);
    written.colors(5, 0) = 17;
    written.scalars.emplace_back("distance", mesh.V.col(2));
    write_mesh(directory / "a.ply", mesh, written);
    VertexAttributes read;
    (void)read_mesh(directory / "a.ply", nullptr, &read);
    EXPECT_EQ(read.normals, written.normals);
    EXPECT_EQ(read.colors, written.colors);
    ASSERT_EQ(read.scalars.size(), 1U);
    EXPECT_EQ(read.scalars[0].first, "distance");
    EXPECT_EQ(read.scalars[0].second, written.scalars[0].second);
    write_mesh(directory / "a.obj", mesh, written);
    (void)read_mesh(directory / "a.obj", nullptr, &read);
    EXPECT_EQ(read.colors, written.colors);
}

TEST(ReadMesh, FromFilesByExtension) {
    const test::TemporaryDirectory directory;
    test::write_bytes(directory / "a.PLY", binary_ply(true));
    test::write_bytes(directory / "b.stl", binary_stl());
    expect_square(read_mesh(directory / "a.PLY"));
    expect_square(read_mesh(directory / "b.stl"));
}

// Every malformed input gives an IoError whose message names the source and the problem.
struct Malformed {
    const char* name;
    MeshFormat format;
    std::string bytes;
    const char* expected;  // a substring of the message
};

class MalformedInput : public ::testing::TestWithParam<Malformed> {};

TEST_P(MalformedInput, GivesAOneLineIoError) {
    const Malformed& input = GetParam();
    try {
        (void)parse(input.bytes, input.format);
        FAIL() << "expected IoError";
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind("test: ", 0), 0u) << message;
        EXPECT_NE(message.find(input.expected), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

std::string truncated(std::string bytes, std::size_t drop) {
    return bytes.substr(0, bytes.size() - drop);
}

INSTANTIATE_TEST_SUITE_P(
    Files, MalformedInput,
    ::testing::Values(
        Malformed{"PlyTruncated", MeshFormat::Ply, truncated(binary_ply(false), 7), "truncated"},
        Malformed{"PlyCountsTooLarge", MeshFormat::Ply, binary_ply(false, 1 << 30),
                  "more than the file can hold"},
        Malformed{"PlyNoMagic", MeshFormat::Ply, "plx\n", "not a PLY file"},
        Malformed{"PlyEmpty", MeshFormat::Ply, "", "not a PLY file"},
        Malformed{"PlyNoEndHeader", MeshFormat::Ply, "ply\nformat ascii 1.0\nelement vertex 1\n",
                  "end_header"},
        Malformed{"PlyBadType", MeshFormat::Ply,
                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n",
                  "unknown property type"},
        Malformed{"PlyNoXyz", MeshFormat::Ply,
                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n",
                  "lacks an x, y or z"},
        Malformed{"PlyTextInNumbers", MeshFormat::Ply,
                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
                  "y\nproperty float z\nend_header\n1 two 3\n",
                  "malformed number 'two'"},
        Malformed{"PlyHugeIndex", MeshFormat::Ply,
                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
                  "y\nproperty float z\nelement face 1\nproperty list uchar int "
                  "vertex_indices\nend_header\n1 2 3\n3 0 0 9999999999\n",
                  "not a valid integer index"},
        Malformed{"PlyNegativeListLength", MeshFormat::Ply,
                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
                  "y\nproperty float z\nelement face 1\nproperty list int int "
                  "vertex_indices\nend_header\n1 2 3\n-3 0 0 0\n",
                  "invalid list length"},
        Malformed{
            "PlyTextInBinary", MeshFormat::Ply,
            "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\nproperty "
            "double y\nproperty double z\nend_header\nthis is text, not doubles\n",
            "more than the file can hold"},
        Malformed{"OffEmpty", MeshFormat::Off, "", "empty file"},
        Malformed{"OffWrongKeyword", MeshFormat::Off, "PLY\n", "not an OFF file"},
        Malformed{"OffBadCounts", MeshFormat::Off, "OFF\n4 x 0\n", "bad counts"},
        Malformed{"OffTruncated", MeshFormat::Off, "OFF\n4 2 0\n0 0 0\n1 0 0\n",
                  "file ends after 2 of 4 vertices"},
        Malformed{"OffHugeCounts", MeshFormat::Off, "OFF\n2000000000 2000000000 0\n0 0 0\n",
                  "file ends after 1 of"},
        Malformed{"OffBadFace", MeshFormat::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n5 0 1 2\n",
                  "malformed face"},
        Malformed{"OffTextInNumbers", MeshFormat::Off, "OFF\n1 0 0\n0 zero 0\n",
                  "malformed vertex"},
        // More faces than declared: the extra ones were dropped silently.
        Malformed{"OffMoreThanDeclared", MeshFormat::Off,
                  "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n3 0 2 1\n",
                  "line 7: more data than the header's 3 vertices and 1 faces"},
        Malformed{"PlyDataAfterTheElements", MeshFormat::Ply,
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                  "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n5 5 5\n",
                  "more data than the header declares"},
        Malformed{"PlyBinaryBytesAfterTheElements", MeshFormat::Ply, binary_ply(false) + "xyz",
                  "more data than the header declares"},
        Malformed{"ObjBadVertex", MeshFormat::Obj, "v 0 0\n", "line 1: malformed vertex"},
        Malformed{"ObjTextInVertex", MeshFormat::Obj, "v 0 0 0\nv 1 x 0\n",
                  "line 2: malformed vertex"},
        Malformed{"ObjZeroIndex", MeshFormat::Obj, "v 0 0 0\nf 0 1 1\n", "bad face corner '0'"},
        Malformed{"ObjHugeIndex", MeshFormat::Obj, "v 0 0 0\nf 1 1 99999999999\n", "out of range"},
        Malformed{"StlEmpty", MeshFormat::Stl, "", "empty file"},
        Malformed{"StlBinaryTruncated", MeshFormat::Stl, truncated(binary_stl(), 10),
                  "but the file has"},
        Malformed{"StlBinaryCountLies", MeshFormat::Stl,
                  std::string(80, 'x') + bytes_of(std::uint32_t{7}, false) + std::string(50, '\0'),
                  "declares 7 triangles"},
        Malformed{"StlAsciiMissingEnd", MeshFormat::Stl,
                  "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "expected 'endloop'"},
        Malformed{"StlAsciiBadNumber", MeshFormat::Stl,
                  "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\n", "malformed number"},
        Malformed{"StlAsciiNoSolid", MeshFormat::Stl, "facet", "not an STL file"}),
    [](const ::testing::TestParamInfo<Malformed>& param_info) {
        return std::string(param_info.param.name);
    });

TEST(ReadMesh, NanAndInfinityAreReadSoThatValidateCanNameThem) {
    const TriangleMesh mesh =
        parse("OFF\n3 1 0\nnan 0 0\n1 inf 0\n1 1 -infinity\n3 0 1 2\n", MeshFormat::Off);
    EXPECT_TRUE(std::isnan(mesh.V(0, 0)));
    EXPECT_TRUE(std::isinf(mesh.V(1, 1)));
    EXPECT_TRUE(std::isinf(mesh.V(2, 2)));
}

TEST(ReadMesh, FileErrorsNameThePath) {
    const test::TemporaryDirectory directory;
    const auto missing = directory / "missing.ply";
    EXPECT_THROW((void)read_mesh(missing), IoError);
    try {
        (void)read_mesh(missing);
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()),
                  missing.string() + ": cannot open for reading (no such file)");
    }
    test::write_bytes(directory / "empty.obj", "");
    try {
        (void)read_mesh(directory / "empty.obj");
        FAIL();
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()), (directory / "empty.obj").string() + ": empty file");
    }
    test::write_bytes(directory / "mesh.xyz", "1 2 3");
    EXPECT_THROW((void)read_mesh(directory / "mesh.xyz"), IoError);
    EXPECT_THROW((void)read_mesh(directory.path()), IoError);
}

TEST(ReadMesh, ZeroFaceFilesParseAndLeaveTheRefusalToValidate) {
    const TriangleMesh mesh = parse("OFF\n1 0 0\n0 0 0\n", MeshFormat::Off);
    EXPECT_EQ(mesh.V.rows(), 1);
    EXPECT_EQ(mesh.F.rows(), 0);
}

}  // namespace
}  // namespace genflow
