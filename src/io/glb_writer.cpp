// SPDX-License-Identifier: MIT
#include "io/glb_writer.h"

#include <tiny_gltf.h>

#include <cctype>
#include <cmath>
#include <cstring>
#include <sstream>

#include "genflow/exceptions.h"
#include "genflow/operators/normals.h"

namespace genflow::detail {

namespace {

// glTF's colours are linear; a file's sRGB 0–255 are decoded (IEC 61966-2-1).
float linear_channel(std::uint8_t value) {
    const double c = value / 255.0;
    return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

// Appends `values` (float or uint32) to the model's one buffer as a view and an accessor of
// `count` items of `type`; returns the accessor's index.
template <typename T>
int add_accessor(tinygltf::Model& model, const std::vector<T>& values, int type, std::size_t count,
                 int target) {
    std::vector<unsigned char>& data = model.buffers.front().data;
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = values.size() * sizeof(T);
    view.target = target;
    data.resize(data.size() + view.byteLength);
    std::memcpy(data.data() + view.byteOffset, values.data(), view.byteLength);
    model.bufferViews.push_back(view);
    tinygltf::Accessor accessor;
    accessor.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
    accessor.componentType = std::is_same_v<T, float> ? TINYGLTF_COMPONENT_TYPE_FLOAT
                                                      : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    accessor.count = count;
    accessor.type = type;
    model.accessors.push_back(accessor);
    return static_cast<int>(model.accessors.size()) - 1;
}

// An attribute of three floats per vertex; POSITION also gets its bounds, which glTF requires.
int add_vec3(tinygltf::Model& model, const Eigen::MatrixX3d& rows, bool bounds) {
    std::vector<float> values(static_cast<std::size_t>(rows.size()));
    for (Eigen::Index i = 0; i < rows.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            values[static_cast<std::size_t>(3 * i + c)] = static_cast<float>(rows(i, c));
        }
    }
    const int index =
        add_accessor(model, values, TINYGLTF_TYPE_VEC3, static_cast<std::size_t>(rows.rows()),
                     TINYGLTF_TARGET_ARRAY_BUFFER);
    if (bounds && rows.rows() > 0) {
        tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
        for (int c = 0; c < 3; ++c) {
            const auto column =
                Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>>(
                    values.data(), rows.rows(), 3)
                    .col(c);
            accessor.minValues.push_back(column.minCoeff());
            accessor.maxValues.push_back(column.maxCoeff());
        }
    }
    return index;
}

// A vertex value's attribute name: application-specific attributes start with '_' and are
// written in capitals by convention ("distance" → "_DISTANCE").
std::string attribute_name(const std::string& name) {
    std::string result = "_";
    for (const char c : name) {
        result += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    return result;
}

// The attributes beside positions and normals: colours (linear), texture coordinates and the
// named values.
void add_vertex_attributes(tinygltf::Model& model, tinygltf::Primitive& primitive,
                           const VertexAttributes& attributes) {
    if (attributes.colors.rows() > 0) {
        Eigen::MatrixX3d linear(attributes.colors.rows(), 3);
        for (Eigen::Index i = 0; i < linear.rows(); ++i) {
            for (int c = 0; c < 3; ++c) {
                linear(i, c) = linear_channel(attributes.colors(i, c));
            }
        }
        primitive.attributes["COLOR_0"] = add_vec3(model, linear, false);
    }
    if (attributes.uvs.rows() > 0) {
        // glTF's texture origin is the image's top left, OBJ's and PLY's its bottom left.
        std::vector<float> uvs;
        for (Eigen::Index i = 0; i < attributes.uvs.rows(); ++i) {
            uvs.push_back(static_cast<float>(attributes.uvs(i, 0)));
            uvs.push_back(static_cast<float>(1 - attributes.uvs(i, 1)));
        }
        primitive.attributes["TEXCOORD_0"] = add_accessor(
            model, uvs, TINYGLTF_TYPE_VEC2, uvs.size() / 2, TINYGLTF_TARGET_ARRAY_BUFFER);
    }
    for (const auto& [name, values] : attributes.scalars) {
        std::vector<float> floats(values.data(), values.data() + values.size());
        primitive.attributes[attribute_name(name)] = add_accessor(
            model, floats, TINYGLTF_TYPE_SCALAR, floats.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
    }
}

// A matte grey, both sides drawn (an open surface is seen from inside too); vertex colours
// multiply it, so it is white where there are colours.
tinygltf::Material matte_material(bool colored) {
    tinygltf::Material material;
    material.doubleSided = true;
    const double grey = colored ? 1.0 : 0.8;
    material.pbrMetallicRoughness.baseColorFactor = {grey, grey, grey, 1.0};
    material.pbrMetallicRoughness.metallicFactor = 0;
    material.pbrMetallicRoughness.roughnessFactor = 0.8;
    return material;
}

// One mesh, one node, one scene: `mesh` with its attributes, as encode_glb() describes.
tinygltf::Model model_of(const TriangleMesh& mesh, const VertexAttributes& attributes) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "genflow";
    model.buffers.emplace_back();
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.attributes["POSITION"] = add_vec3(model, mesh.V, true);
    primitive.attributes["NORMAL"] = add_vec3(model, vertex_normals(mesh), false);
    add_vertex_attributes(model, primitive, attributes);
    std::vector<std::uint32_t> indices(static_cast<std::size_t>(mesh.F.size()));
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            indices[static_cast<std::size_t>(3 * f + c)] = static_cast<std::uint32_t>(mesh.F(f, c));
        }
    }
    primitive.indices = add_accessor(model, indices, TINYGLTF_TYPE_SCALAR, indices.size(),
                                     TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    model.materials.push_back(matte_material(attributes.colors.rows() > 0));
    primitive.material = 0;
    tinygltf::Mesh gltf_mesh;
    gltf_mesh.primitives.push_back(primitive);
    model.meshes.push_back(gltf_mesh);
    tinygltf::Node node;
    node.mesh = 0;
    model.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.nodes.push_back(0);
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    return model;
}

std::string serialized(tinygltf::Model& model) {
    std::ostringstream stream;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, stream, false, true)) {
        throw IoError("glTF: the writer failed");
    }
    return stream.str();
}

// Frame k's positions and normals as morph target k - 1: their differences from frame 0's.
void add_morph_targets(tinygltf::Model& model, const Eigen::MatrixX3i& faces,
                       const std::vector<Eigen::MatrixX3d>& frames) {
    tinygltf::Primitive& primitive = model.meshes.front().primitives.front();
    const Eigen::MatrixX3d first_normals = vertex_normals(TriangleMesh{frames.front(), faces});
    for (std::size_t k = 1; k < frames.size(); ++k) {
        const Eigen::MatrixX3d normals = vertex_normals(TriangleMesh{frames[k], faces});
        primitive.targets.push_back(
            {{"POSITION", add_vec3(model, frames[k] - frames.front(), true)},
             {"NORMAL", add_vec3(model, normals - first_normals, false)}});
        model.meshes.front().weights.push_back(0);
    }
}

// Frame k at k / fps: at that time target k - 1 has weight 1 and every other 0, and the
// weights run linearly in between, so viewers blend one frame into the next.
void add_frame_animation(tinygltf::Model& model, std::size_t frame_count, double fps) {
    std::vector<float> times;
    std::vector<float> weights;
    for (std::size_t k = 0; k < frame_count; ++k) {
        times.push_back(static_cast<float>(static_cast<double>(k) / fps));
        for (std::size_t target = 0; target + 1 < frame_count; ++target) {
            weights.push_back(target + 1 == k ? 1.0F : 0.0F);
        }
    }
    tinygltf::AnimationSampler sampler;
    sampler.input = add_accessor(model, times, TINYGLTF_TYPE_SCALAR, times.size(), 0);
    tinygltf::Accessor& input = model.accessors[static_cast<std::size_t>(sampler.input)];
    input.minValues = {times.front()};
    input.maxValues = {times.back()};
    sampler.output = add_accessor(model, weights, TINYGLTF_TYPE_SCALAR, weights.size(), 0);
    sampler.interpolation = "LINEAR";
    tinygltf::AnimationChannel channel;
    channel.sampler = 0;
    channel.target_node = 0;
    channel.target_path = "weights";
    tinygltf::Animation animation;
    animation.name = "frames";
    animation.samplers.push_back(sampler);
    animation.channels.push_back(channel);
    model.animations.push_back(animation);
}

}  // namespace

std::string encode_glb(const TriangleMesh& mesh, const VertexAttributes& attributes) {
    tinygltf::Model model = model_of(mesh, attributes);
    return serialized(model);
}

std::string encode_animated_glb(const Eigen::MatrixX3i& faces,
                                const std::vector<Eigen::MatrixX3d>& frames,
                                const VertexAttributes& attributes, double frames_per_second) {
    tinygltf::Model model = model_of(TriangleMesh{frames.front(), faces}, attributes);
    if (frames.size() > 1) {
        add_morph_targets(model, faces, frames);
        add_frame_animation(model, frames.size(), frames_per_second);
    }
    return serialized(model);
}

}  // namespace genflow::detail
