// SPDX-License-Identifier: MIT
#include "genflow/io/write_animation.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/io/read_file.h"
#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// A sphere breathing: radius 1, 1.5, 2.
std::vector<Eigen::MatrixX3d> breathing(const TriangleMesh& sphere) {
    return {sphere.V, 1.5 * sphere.V, 2 * sphere.V};
}

tinygltf::Model read_glb(const std::filesystem::path& path) {
    const std::string bytes = read_file(path);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error;
    std::string warning;
    EXPECT_TRUE(loader.LoadBinaryFromMemory(&model, &error, &warning,
                                            reinterpret_cast<const unsigned char*>(bytes.data()),
                                            static_cast<unsigned>(bytes.size())))
        << error;
    return model;
}

std::vector<float> floats_of(const tinygltf::Model& model, int accessor_index) {
    const tinygltf::Accessor& accessor =
        model.accessors.at(static_cast<std::size_t>(accessor_index));
    const tinygltf::BufferView& view =
        model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
    const auto* data = reinterpret_cast<const float*>(model.buffers.at(0).data.data() +
                                                      view.byteOffset + accessor.byteOffset);
    return {data, data + view.byteLength / sizeof(float)};
}

// Frame k is the first frame plus morph target k - 1, whose weight the animation holds at 1 at
// frame k's time (k / fps) and at 0 at the others'.
TEST(WriteAnimation, PlaysTheFramesAsMorphTargetsOfTheFirst) {
    const test::TemporaryDirectory directory;
    const TriangleMesh sphere = make_icosphere(1);
    VertexAttributes attributes;
    attributes.colors = VertexColors::Constant(sphere.V.rows(), 3, 200);
    write_animation(directory / "breath.glb", sphere.F, breathing(sphere), attributes,
                    {.frames_per_second = 10});
    const tinygltf::Model model = read_glb(directory / "breath.glb");
    const tinygltf::Primitive& primitive = model.meshes.at(0).primitives.at(0);
    ASSERT_EQ(primitive.targets.size(), 2U);
    EXPECT_EQ(model.meshes[0].weights, std::vector<double>({0, 0}));
    EXPECT_TRUE(primitive.attributes.contains("COLOR_0"));
    const std::vector<float> base = floats_of(model, primitive.attributes.at("POSITION"));
    const std::vector<float> last = floats_of(model, primitive.targets[1].at("POSITION"));
    for (std::size_t i = 0; i < base.size(); ++i) {
        EXPECT_NEAR(base[i] + last[i], 2 * base[i], 1e-6);
    }
    ASSERT_EQ(model.animations.size(), 1U);
    const tinygltf::Animation& animation = model.animations[0];
    EXPECT_EQ(animation.channels.at(0).target_path, "weights");
    EXPECT_EQ(animation.channels[0].target_node, 0);
    const tinygltf::AnimationSampler& sampler = animation.samplers.at(0);
    EXPECT_EQ(sampler.interpolation, "LINEAR");
    EXPECT_EQ(floats_of(model, sampler.input), std::vector<float>({0.0F, 0.1F, 0.2F}));
    EXPECT_EQ(floats_of(model, sampler.output), std::vector<float>({0, 0, 1, 0, 0, 1}));
}

TEST(WriteAnimation, OneFrameIsAStillMesh) {
    const test::TemporaryDirectory directory;
    const TriangleMesh sphere = make_icosphere(1);
    write_animation(directory / "still.glb", sphere.F, {sphere.V});
    const tinygltf::Model model = read_glb(directory / "still.glb");
    EXPECT_TRUE(model.animations.empty());
    EXPECT_TRUE(model.meshes.at(0).primitives.at(0).targets.empty());
}

TEST(WriteAnimation, RefusesWhatItCannotPlay) {
    const test::TemporaryDirectory directory;
    const TriangleMesh sphere = make_icosphere(1);
    EXPECT_THROW(write_animation(directory / "a.ply", sphere.F, breathing(sphere)), IoError);
    EXPECT_THROW(write_animation(directory / "a.glb", sphere.F, {}), InvalidInput);
    std::vector<Eigen::MatrixX3d> frames = breathing(sphere);
    frames[1].conservativeResize(3, 3);
    EXPECT_THROW(write_animation(directory / "a.glb", sphere.F, frames), InvalidInput);
    frames = breathing(sphere);
    frames[2](0, 0) = std::numeric_limits<double>::infinity();
    EXPECT_THROW(write_animation(directory / "a.glb", sphere.F, frames), InvalidInput);
    EXPECT_THROW(write_animation(directory / "a.glb", sphere.F, breathing(sphere), {},
                                 {.frames_per_second = 0}),
                 InvalidInput);
    EXPECT_FALSE(std::filesystem::exists(directory / "a.glb"));
}

}  // namespace
}  // namespace genflow
