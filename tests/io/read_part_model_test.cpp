// SPDX-License-Identifier: MIT
// Part files: the three JSON layouts, labels and sparse weights, and clear refusals.
#include "genflow/io/read_part_model.h"

#include <gtest/gtest.h>

#include <fstream>

#include "genflow/exceptions.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

void write(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

// Throws IoError whose message names `file`.
void expect_refused(const PartFiles& files, Eigen::Index vertices,
                    const std::filesystem::path& file) {
    try {
        (void)read_part_model(files, vertices);
        ADD_FAILURE() << "accepted";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find(file.filename().string()), std::string::npos)
            << e.what();
    }
}

TEST(ReadPartModel, ReadsTheThreeLayouts) {
    const test::TemporaryDirectory d;
    write(d / "labels.txt", "# comment\n0\n1\n1\n2\n");
    write(d / "named.json",
          R"({"parts": [{"name": "a", "parent": null, "joint_center": [0, 0, 0]},
                        {"name": "b", "parent": "a", "joint_center": [1, 0, 0]},
                        {"name": "c", "parent": "b", "joint_center": [2, 0, 0]}],
              "labels": "labels.txt"})");
    const PartModel named = read_part_model({d / "named.json"}, 4);
    ASSERT_EQ(named.parts.size(), 3U);
    EXPECT_EQ(named.parts[2].parent, 1);
    EXPECT_EQ(named.parts[2].joint_centre, Eigen::Vector3d(2, 0, 0));
    EXPECT_EQ(named.weights(3, 2), 1);

    write(d / "bones.json",
          R"({"bones": [{"index": 0, "parent_bone": null, "joint_center": [0, 0, 0]},
                        {"index": 1, "parent_bone": 0, "joint_center": [1, 0, 0]}]})");
    write(d / "weights.txt", "# sparse\n0 0 1\n1 0 0.25\n1 1 0.75\n2 1 1\n");
    const PartModel bones = read_part_model({d / "bones.json", std::nullopt, d / "weights.txt"}, 3);
    EXPECT_EQ(bones.parts[1].parent, 0);
    EXPECT_DOUBLE_EQ(bones.weights(1, 1), 0.75);
    // A skeleton whose root joint has several bones (the libigl elephant's): a forest.
    write(d / "forest.json",
          R"({"bones": [{"index": 0, "parent_bone": null, "joint_center": [0, 0, 0]},
                        {"index": 1, "parent_bone": null, "joint_center": [0, 0, 0]}]})");
    const PartModel forest =
        read_part_model({d / "forest.json", std::nullopt, d / "weights.txt"}, 3);
    EXPECT_EQ(forest.parts[0].parent, -1);
    EXPECT_EQ(forest.parts[1].parent, -1);

    write(d / "smpl.json",
          R"({"parts": ["hips", "leg"], "parent": {"hips": null, "leg": "hips"},
              "joint_centers": {"pose_a": {"hips": [0, 0, 0], "leg": [0, -1, 0]},
                                "pose_b": {"hips": [0, 0, 0], "leg": [0, -2, 0]}}})");
    write(d / "two.txt", "0\n1\n");
    const PartModel smpl =
        read_part_model({d / "smpl.json", d / "two.txt", std::nullopt, "pose_b"}, 2);
    EXPECT_EQ(smpl.parts[1].joint_centre, Eigen::Vector3d(0, -2, 0));
    expect_refused({d / "smpl.json", d / "two.txt"}, 2, d / "smpl.json");  // which pose?
}

// A rig's template in one of its poses: each joint centre moves with the part below it, by the
// part's 4×4 world transform (rows), as the rig posed the mesh.
TEST(ReadPartModel, MovesTheJointCentresToTheTemplatesPose) {
    const test::TemporaryDirectory d;
    write(d / "weights.txt", "0 0 1\n1 1 1\n");
    // Bone 1 turned a quarter about z and moved by (1, 2, 3): its joint (1, 0, 0) goes to
    // (0, 1, 0) + (1, 2, 3).
    write(d / "bones.json",
          R"({"bones": [{"index": 0, "parent_bone": null, "joint_center": [0, 0, 0]},
                        {"index": 1, "parent_bone": 0, "joint_center": [1, 0, 0]}],
              "pose_bone_transforms_4x4": {
                "pose1": [[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]],
                          [[0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]]}})");
    PartFiles bones{d / "bones.json", std::nullopt, d / "weights.txt"};
    const Eigen::Vector3d posed(1, 3, 3);
    bones.pose = "pose1";
    EXPECT_TRUE(read_part_model(bones, 2).parts[1].joint_centre.isApprox(posed));
    bones.pose.clear();
    bones.template_name = "arm_pose1";  // named by the template's last word
    EXPECT_TRUE(read_part_model(bones, 2).parts[1].joint_centre.isApprox(posed));
    bones.template_name = "arm_rest";  // no such pose: the rest pose
    EXPECT_EQ(read_part_model(bones, 2).parts[1].joint_centre, Eigen::Vector3d(1, 0, 0));
    bones.pose = "pose9";
    expect_refused(bones, 2, d / "bones.json");

    // The MakeHuman layout: a world transform per part name.
    write(d / "named.json",
          R"({"parts": [{"name": "a", "parent": null, "joint_center": [0, 0, 0]},
                        {"name": "b", "parent": "a", "joint_center": [1, 0, 0]}],
              "poses": {"pose2": {
                "a": {"world_transform_4x4": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]},
                "b": {"world_transform_4x4": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]]}}}})");
    PartFiles named{d / "named.json", std::nullopt, d / "weights.txt"};
    named.template_name = "body_pose2";
    EXPECT_EQ(read_part_model(named, 2).parts[1].joint_centre, Eigen::Vector3d(1, 0, 5));
    // A part without its transform, and a transform of three rows, are refused.
    write(d / "partial.json",
          R"({"parts": [{"name": "a", "parent": null, "joint_center": [0, 0, 0]},
                        {"name": "b", "parent": "a", "joint_center": [1, 0, 0]}],
              "poses": {"pose2": {
                "a": {"world_transform_4x4": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}}}})");
    expect_refused({d / "partial.json", std::nullopt, d / "weights.txt", "pose2"}, 2,
                   d / "partial.json");
    // A pose asked of a file without poses is refused; a template name is not.
    write(d / "rest.json",
          R"({"parts": [{"name": "a", "parent": null, "joint_center": [0, 0, 0]},
                        {"name": "b", "parent": "a", "joint_center": [1, 0, 0]}]})");
    expect_refused({d / "rest.json", std::nullopt, d / "weights.txt", "pose1"}, 2, d / "rest.json");
    EXPECT_NO_THROW((void)read_part_model(
        {d / "rest.json", std::nullopt, d / "weights.txt", "", "body_pose1"}, 2));

    // The SMPL layout finds its entry by the template's name too.
    write(d / "smpl.json",
          R"({"parts": ["hips", "leg"], "parent": {"hips": null, "leg": "hips"},
              "joint_centers": {"scan_a": {"hips": [0, 0, 0], "leg": [0, -1, 0]},
                                "scan_b": {"hips": [0, 0, 0], "leg": [0, -2, 0]}}})");
    EXPECT_EQ(read_part_model({d / "smpl.json", std::nullopt, d / "weights.txt", "", "scan_b"}, 2)
                  .parts[1]
                  .joint_centre,
              Eigen::Vector3d(0, -2, 0));
}

TEST(ReadPartModel, RefusesFilesThatDoNotFitAndNamesThem) {
    const test::TemporaryDirectory d;
    write(d / "tree.json",
          R"({"parts": [{"name": "a", "parent": null, "joint_center": [0, 0, 0]},
                        {"name": "b", "parent": "a", "joint_center": [1, 0, 0]}]})");
    write(d / "labels.txt", "0\n1\n1\n");
    EXPECT_NO_THROW((void)read_part_model({d / "tree.json", d / "labels.txt"}, 3));
    expect_refused({d / "tree.json", d / "labels.txt"}, 4, d / "labels.txt");  // vertex count
    write(d / "range.txt", "0\n2\n1\n");
    expect_refused({d / "tree.json", d / "range.txt"}, 3, d / "range.txt");  // label out of range
    write(d / "text.txt", "0\nx\n1\n");
    expect_refused({d / "tree.json", d / "text.txt"}, 3, d / "text.txt");
    write(d / "sum.txt", "0 0 0.5\n1 1 1\n2 1 1\n");
    expect_refused({d / "tree.json", std::nullopt, d / "sum.txt"}, 3, d / "sum.txt");
    write(d / "cycle.json",
          R"({"parts": [{"name": "a", "parent": "b", "joint_center": [0, 0, 0]},
                        {"name": "b", "parent": "a", "joint_center": [1, 0, 0]}]})");
    expect_refused({d / "cycle.json", d / "labels.txt"}, 3, d / "cycle.json");
    write(d / "unknown.json",
          R"({"parts": [{"name": "a", "parent": null, "joint_center": [0, 0, 0]},
                        {"name": "b", "parent": "z", "joint_center": [1, 0, 0]}]})");
    expect_refused({d / "unknown.json", d / "labels.txt"}, 3, d / "unknown.json");
    write(d / "broken.json", "{\"parts\": [");
    expect_refused({d / "broken.json", d / "labels.txt"}, 3, d / "broken.json");
    expect_refused({d / "tree.json"}, 3, d / "tree.json");  // no per-vertex file
    expect_refused({d / "missing.json", d / "labels.txt"}, 3, d / "missing.json");
}

}  // namespace
}  // namespace genflow
