// SPDX-License-Identifier: MIT
// Texture coordinates read, written and carried: per vertex, or per face corner where a seam
// gives a vertex two.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/io/read_mesh.h"
#include "genflow/io/write_mesh.h"
#include "genflow/matching/carry_attributes.h"
#include "genflow/matching/correspondence.h"
#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

VertexAttributes read_obj(const std::string& text, std::vector<std::string>* warnings = nullptr) {
    VertexAttributes attributes;
    (void)parse_mesh(text, MeshFormat::Obj, "t.obj", warnings, &attributes);
    return attributes;
}

// The (u, v) at corner c of face f, whichever way the attributes hold it.
Eigen::RowVector2d corner_uv(const TriangleMesh& mesh, const VertexAttributes& attributes,
                             Eigen::Index f, int c) {
    return attributes.corner_uv_faces.rows() > 0
               ? Eigen::RowVector2d(attributes.corner_uvs.row(attributes.corner_uv_faces(f, c)))
               : Eigen::RowVector2d(attributes.uvs.row(mesh.F(f, c)));
}

// A square of two triangles whose shared diagonal is a seam: vertex 0 has (0, 0) in the first
// face and (0.5, 0.5) in the second.
constexpr const char* kSeamedSquare =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.5 0.5\nvt 0 1\n"
    "f 1/1 2/2 3/3\nf 1/4 3/3 4/5\n";

TEST(TextureCoordinates, ObjWithoutSeamsGivesThemPerVertexWithItsNormals) {
    // A pentagon, split into a fan: its corners' records must follow the split.
    const VertexAttributes read = read_obj(
        "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\n"
        "vt 0.5 0.25\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
        "f 1/2/1 2/3/1 3/1/1 4/4/1 5/5/1\n");
    ASSERT_EQ(read.uvs.rows(), 5);
    EXPECT_EQ(read.corner_uv_faces.rows(), 0);
    EXPECT_EQ(read.uvs.row(0), Eigen::RowVector2d(0, 0));
    EXPECT_EQ(read.uvs.row(2), Eigen::RowVector2d(0.5, 0.25));
    EXPECT_EQ(read.uvs.row(4), Eigen::RowVector2d(0, 1));
    ASSERT_EQ(read.normals.rows(), 5);
    EXPECT_EQ(read.normals.row(3), Eigen::RowVector3d(0, 0, 1));
}

TEST(TextureCoordinates, ObjWithASeamGivesThemPerCorner) {
    std::vector<std::string> warnings;
    const TriangleMesh mesh = parse_mesh(kSeamedSquare, MeshFormat::Obj, "t.obj");
    const VertexAttributes read = read_obj(kSeamedSquare, &warnings);
    EXPECT_TRUE(warnings.empty());
    EXPECT_EQ(read.uvs.rows(), 0);
    ASSERT_EQ(read.corner_uv_faces.rows(), 2);
    EXPECT_EQ(corner_uv(mesh, read, 0, 0), Eigen::RowVector2d(0, 0));
    EXPECT_EQ(corner_uv(mesh, read, 1, 0), Eigen::RowVector2d(0.5, 0.5));
    EXPECT_EQ(corner_uv(mesh, read, 1, 2), Eigen::RowVector2d(0, 1));
}

TEST(TextureCoordinates, ObjSaysWhatItLeavesOutAndRefusesUndefinedRecords) {
    std::vector<std::string> warnings;
    (void)read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1 2 3\n", &warnings);
    ASSERT_EQ(warnings.size(), 1U);
    EXPECT_EQ(warnings[0], "t.obj: texture coordinates (vt) that no face uses, left out");
    warnings.clear();
    (void)read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n",
                   &warnings);
    ASSERT_EQ(warnings.size(), 1U);
    EXPECT_EQ(warnings[0], "t.obj: texture coordinates (vt) on some faces only, left out");
    warnings.clear();
    (void)read_obj(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 1 0\nf 1//1 2//1 3//1\nf 2//2 4//2 "
        "3//2\n",
        &warnings);
    ASSERT_EQ(warnings.size(), 1U);
    EXPECT_EQ(warnings[0], "t.obj: normals (vn) that differ between a vertex's corners, left out");
    try {
        (void)read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n");
        FAIL() << "an undefined vt was accepted";
    } catch (const IoError& error) {
        EXPECT_STREQ(error.what(),
                     "t.obj: line 5: a face corner names a vt record that is not defined");
    }
    EXPECT_THROW((void)read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt x 0\nf 1/1 2/1 3/1\n"), IoError);
}

TEST(TextureCoordinates, PlyReadsThemByEachCommonName) {
    for (const auto& [u, v] : {std::pair{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}}) {
        const std::string text =
            std::string(
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                "property float y\nproperty float z\nproperty float ") +
            u + "\nproperty float " + v +
            "\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 0.5\n3 0 1 2\n";
        VertexAttributes read;
        (void)parse_mesh(text, MeshFormat::Ply, "t.ply", nullptr, &read);
        ASSERT_EQ(read.uvs.rows(), 3) << u;
        EXPECT_EQ(read.uvs.row(2), Eigen::RowVector2d(0, 0.5)) << u;
        EXPECT_TRUE(read.scalars.empty()) << u;
    }
}

TEST(TextureCoordinates, PlyFaceTexcoordListsGiveThemPerCornerAtASeam) {
    const std::string text =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
        "property list uchar float texcoord\nproperty uchar red\nend_header\n"
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 6 0 0 1 0 1 1 7\n3 0 2 3 6 0.5 0.5 1 1 0 1 7\n";
    VertexAttributes read;
    std::vector<std::string> warnings;
    const TriangleMesh mesh = parse_mesh(text, MeshFormat::Ply, "t.ply", &warnings, &read);
    ASSERT_EQ(warnings.size(), 1U);
    EXPECT_EQ(warnings[0], "t.ply: face properties left out: red");
    ASSERT_EQ(read.corner_uv_faces.rows(), 2);
    EXPECT_EQ(corner_uv(mesh, read, 0, 0), Eigen::RowVector2d(0, 0));
    EXPECT_EQ(corner_uv(mesh, read, 1, 0), Eigen::RowVector2d(0.5, 0.5));
    EXPECT_EQ(corner_uv(mesh, read, 1, 1), Eigen::RowVector2d(1, 1));
}

// Written and read back: per vertex by OBJ, PLY (text and binary) and glTF, per corner by OBJ
// and PLY; the formats that hold none say so.
TEST(TextureCoordinates, AreWrittenAndReadBack) {
    const test::TemporaryDirectory directory;
    const TriangleMesh seamed = parse_mesh(kSeamedSquare, MeshFormat::Obj, "t.obj");
    const VertexAttributes per_corner = read_obj(kSeamedSquare);
    VertexAttributes per_vertex;
    per_vertex.uvs = seamed.V.leftCols(2) / 2;
    for (const VertexAttributes* written : {&std::as_const(per_vertex), &per_corner}) {
        for (const char* name : {"a.obj", "a.ply", "b.ply"}) {
            WriteMeshOptions options;
            if (std::string(name) == "b.ply") {
                options.ply_encoding = PlyEncoding::BinaryLittleEndian;
            }
            std::vector<std::string> warnings;
            write_mesh(directory / name, seamed, *written, options, &warnings);
            EXPECT_TRUE(warnings.empty()) << name;
            VertexAttributes read;
            const TriangleMesh back = read_mesh(directory / name, nullptr, &read);
            EXPECT_EQ(read.corner_uv_faces.rows() > 0, written == &per_corner) << name;
            for (Eigen::Index f = 0; f < seamed.F.rows(); ++f) {
                for (int c = 0; c < 3; ++c) {
                    EXPECT_EQ(corner_uv(back, read, f, c), corner_uv(seamed, *written, f, c))
                        << name << " face " << f << " corner " << c;
                }
            }
        }
    }
    for (const char* name : {"a.off", "a.stl", "a.glb"}) {
        std::vector<std::string> warnings;
        write_mesh(directory / name, seamed, per_corner, {}, &warnings);
        ASSERT_EQ(warnings.size(), 1U) << name;
        EXPECT_NE(warnings[0].find("texture coordinates per corner"), std::string::npos);
    }
    VertexAttributes bad = per_corner;
    bad.corner_uv_faces(1, 2) = 9;
    EXPECT_THROW(write_mesh(directory / "bad.obj", seamed, bad), InvalidInput);
    bad = per_vertex;
    bad.uvs.conservativeResize(2, 2);
    EXPECT_THROW(write_mesh(directory / "bad.ply", seamed, bad), InvalidInput);
}

// Carried to another mesh through a correspondence: per vertex they are interpolated; per
// corner each target vertex takes those of the face it lands on.
TEST(TextureCoordinates, AreCarriedToATargetPerVertex) {
    const TriangleMesh sphere = make_icosphere(2);
    const std::vector<SurfacePoint> onto_itself = closest_points(sphere.V, sphere);
    VertexAttributes per_vertex;
    per_vertex.uvs = sphere.V.leftCols(2);
    const VertexAttributes carried = carry_attributes(sphere, per_vertex, sphere, onto_itself);
    ASSERT_EQ(carried.uvs.rows(), sphere.V.rows());
    EXPECT_LT((carried.uvs - per_vertex.uvs).cwiseAbs().maxCoeff(), 1e-12);

    VertexAttributes per_corner;  // each face its own patch of the texture: all seams
    per_corner.corner_uvs.resize(3 * sphere.F.rows(), 2);
    per_corner.corner_uv_faces.resize(sphere.F.rows(), 3);
    for (Eigen::Index f = 0; f < sphere.F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            per_corner.corner_uv_faces(f, c) = static_cast<int>(3 * f + c);
            per_corner.corner_uvs.row(3 * f + c) = sphere.V.row(sphere.F(f, c)).leftCols(2);
        }
    }
    const VertexAttributes from_corners = carry_attributes(sphere, per_corner, sphere, onto_itself);
    ASSERT_EQ(from_corners.uvs.rows(), sphere.V.rows());
    EXPECT_EQ(from_corners.corner_uv_faces.rows(), 0);
    EXPECT_LT((from_corners.uvs - per_vertex.uvs).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace genflow
