// SPDX-License-Identifier: MIT
#include "genflow/io/read_part_model.h"

#include <charconv>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/io/read_file.h"
#include "io/parse_context.h"

namespace genflow {

namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& problem) {
    throw IoError(file.string() + ": " + problem);
}

Eigen::Vector3d point(const std::filesystem::path& file, const json& value,
                      const std::string& what) {
    if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
        !value[2].is_number()) {
        fail(file, what + " must be an array of three numbers");
    }
    return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
}

// A 4×4 transform given as four rows of four numbers; its top three rows act on points.
Eigen::Matrix4d transform(const std::filesystem::path& file, const json& value,
                          const std::string& what) {
    Eigen::Matrix4d matrix;
    bool valid = value.is_array() && value.size() == 4;
    for (int r = 0; r < 4 && valid; ++r) {
        const json& row = value[static_cast<std::size_t>(r)];
        valid = row.is_array() && row.size() == 4;
        for (int c = 0; c < 4 && valid; ++c) {
            valid = row[static_cast<std::size_t>(c)].is_number();
            if (valid) {
                matrix(r, c) = row[static_cast<std::size_t>(c)].get<double>();
            }
        }
    }
    if (!valid || !matrix.allFinite()) {
        fail(file, what + " must be four rows of four finite numbers");
    }
    return matrix;
}

Eigen::Vector3d moved(const Eigen::Matrix4d& transform, const Eigen::Vector3d& point) {
    return transform.topLeftCorner<3, 3>() * point + transform.topRightCorner<3, 1>();
}

std::string keys_of(const json& table) {
    std::string keys;
    for (const auto& [key, unused] : table.items()) {
        keys += (keys.empty() ? "" : ", ") + key;
    }
    return keys;
}

// The pose the template is in, a key of `poses` (a part file's table of poses): the one asked
// for (refused if not there), else the template's name or its last '_'-separated word if
// either is a key ("arm_pose1": "pose1"); std::nullopt for none of them.
std::optional<std::string> chosen_pose(const std::filesystem::path& file, const json& poses,
                                       const PartFiles& files) {
    if (!poses.is_object()) {
        fail(file, "its poses must be an object keyed by pose name");
    }
    if (!files.pose.empty()) {
        if (!poses.contains(files.pose)) {
            fail(file, "no pose '" + files.pose + "' (it has " + keys_of(poses) + ")");
        }
        return files.pose;
    }
    const std::string& name = files.template_name;
    if (!name.empty() && poses.contains(name)) {
        return name;
    }
    const auto underscore = name.rfind('_');
    if (underscore != std::string::npos && poses.contains(name.substr(underscore + 1))) {
        return name.substr(underscore + 1);
    }
    return std::nullopt;
}

// Moves each joint centre with the part below it to the template's pose, if the file has a
// table of poses under `key` and the template is in one of them (else they stay at rest; a
// pose asked of a file without the table is refused). `transform_of(entry, pose, p)` is part
// p's 4×4 transform in the pose's entry of the table.
template <typename TransformOf>
void move_to_pose(const std::filesystem::path& file, const json& document, const char* key,
                  const PartFiles& files, std::vector<Part>& parts,
                  const TransformOf& transform_of) {
    if (!document.contains(key)) {
        if (!files.pose.empty()) {
            fail(file, "has no poses, so no pose '" + files.pose + "'");
        }
        return;
    }
    const json& poses = document[key];
    if (const auto pose = chosen_pose(file, poses, files)) {
        for (std::size_t p = 0; p < parts.size(); ++p) {
            parts[p].joint_centre =
                moved(transform_of(poses[*pose], *pose, p), parts[p].joint_centre);
        }
    }
}

// The non-empty, non-comment lines of a text file, split on whitespace.
std::vector<std::vector<std::string>> rows(const std::filesystem::path& file) {
    const std::string bytes = read_file(file);
    detail::TextScanner text(bytes);
    std::vector<std::vector<std::string>> result;
    while (!text.at_end()) {
        const std::string line(text.next_line());
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') {
            continue;
        }
        std::istringstream fields(line);
        std::vector<std::string> row;
        for (std::string field; fields >> field;) {
            row.push_back(field);
        }
        result.push_back(std::move(row));
    }
    return result;
}

template <typename T>
T number(const std::filesystem::path& file, const std::string& text, std::size_t line) {
    T value{};
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) {
        fail(file, "entry " + std::to_string(line + 1) + ": '" + text + "' is not a number");
    }
    return value;
}

std::vector<Part> parse_tree(const std::filesystem::path& file, const json& document,
                             const PartFiles& files) {
    std::vector<Part> parts;
    std::map<std::string, int> index_of;
    const auto add_names = [&] {
        for (std::size_t p = 0; p < parts.size(); ++p) {
            if (!index_of.emplace(parts[p].name, static_cast<int>(p)).second) {
                fail(file, "two parts are named '" + parts[p].name + "'");
            }
        }
    };
    const auto parent_index = [&](const json& parent) {
        if (parent.is_null()) {
            return -1;
        }
        if (!parent.is_string() || !index_of.contains(parent.get<std::string>())) {
            fail(file, "parent " + parent.dump() + " is not a part name");
        }
        return index_of.at(parent.get<std::string>());
    };
    if (document.contains("bones")) {  // libigl skeletons: bones with parent indices
        const json& bones = document["bones"];
        if (!bones.is_array()) {
            fail(file, "\"bones\" must be an array");
        }
        for (std::size_t b = 0; b < bones.size(); ++b) {
            const json& parent = bones[b].value("parent_bone", json());
            if (!parent.is_null() && !parent.is_number_integer()) {
                fail(file, "bone " + std::to_string(b) + ": parent_bone must be an index or null");
            }
            parts.push_back({"bone" + std::to_string(b), parent.is_null() ? -1 : parent.get<int>(),
                             point(file, bones[b].value("joint_center", json()),
                                   "bone " + std::to_string(b) + " joint_center")});
        }
        // The joint at a bone's head moves with the bone.
        move_to_pose(file, document, "pose_bone_transforms_4x4", files, parts,
                     [&](const json& transforms, const std::string& pose, std::size_t b) {
                         if (!transforms.is_array() || transforms.size() != parts.size()) {
                             fail(file, "pose '" + pose + "' must hold one transform per bone (" +
                                            std::to_string(parts.size()) + ")");
                         }
                         return transform(file, transforms[b],
                                          "pose '" + pose + "' bone " + std::to_string(b));
                     });
        return parts;
    }
    if (!document.contains("parts") || !document["parts"].is_array()) {
        fail(file, "no \"parts\" or \"bones\" array");
    }
    const json& list = document["parts"];
    if (!list.empty() && list[0].is_string()) {  // names, with "parent" and "joint_centers"
        for (const json& name : list) {
            if (!name.is_string()) {
                fail(file, "\"parts\" mixes names and objects");
            }
            parts.push_back({name.get<std::string>(), -1, Eigen::Vector3d::Zero()});
        }
        add_names();
        const json& parents = document.value("parent", json::object());
        const json& centres = document.value("joint_centers", json::object());
        if (!centres.is_object() || centres.empty()) {
            fail(file, "no \"joint_centers\"");
        }
        std::string chosen;
        if (const auto pose = chosen_pose(file, centres, files)) {
            chosen = *pose;
        } else if (centres.size() == 1) {
            chosen = centres.begin().key();
        } else {
            fail(file, "several poses in \"joint_centers\" (" + keys_of(centres) +
                           "); choose one (--parts-pose)");
        }
        for (Part& part : parts) {
            part.parent = parent_index(parents.value(part.name, json()));
            const json& centre = centres[chosen].value(part.name, json());
            part.joint_centre = point(file, centre, "joint centre of '" + part.name + "'");
        }
        return parts;
    }
    for (std::size_t p = 0; p < list.size(); ++p) {  // objects with name, parent, joint_center
        if (!list[p].is_object() || !list[p].contains("name") || !list[p]["name"].is_string()) {
            fail(file, "part " + std::to_string(p) + " needs a \"name\"");
        }
        parts.push_back({list[p]["name"].get<std::string>(), -1,
                         point(file, list[p].value("joint_center", json()),
                               "joint_center of '" + list[p]["name"].get<std::string>() + "'")});
    }
    add_names();
    for (std::size_t p = 0; p < list.size(); ++p) {
        parts[p].parent = parent_index(list[p].value("parent", json()));
    }
    // The joint linking a part to its parent moves with the part.
    move_to_pose(file, document, "poses", files, parts,
                 [&](const json& transforms, const std::string& pose, std::size_t p) {
                     const std::string& name = parts[p].name;
                     const std::string what = "pose '" + pose + "' part '" + name + "'";
                     if (!transforms.is_object() || !transforms.contains(name) ||
                         !transforms[name].is_object()) {
                         fail(file, what + " has no world_transform_4x4");
                     }
                     return transform(file, transforms[name].value("world_transform_4x4", json()),
                                      what);
                 });
    return parts;
}

Eigen::MatrixXd read_labels(const std::filesystem::path& file, Eigen::Index vertices, int parts) {
    const auto lines = rows(file);
    if (static_cast<Eigen::Index>(lines.size()) != vertices) {
        fail(file, std::to_string(lines.size()) + " labels for a template of " +
                       std::to_string(vertices) + " vertices");
    }
    Eigen::VectorXi labels(vertices);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (lines[i].size() != 1) {
            fail(file, "line for vertex " + std::to_string(i) + " must hold one label");
        }
        labels[static_cast<Eigen::Index>(i)] = number<int>(file, lines[i][0], i);
    }
    try {
        return weights_from_labels(labels, parts);
    } catch (const InvalidInput& e) {
        fail(file, e.what());
    }
}

Eigen::MatrixXd read_weights(const std::filesystem::path& file, Eigen::Index vertices, int parts) {
    Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(vertices, parts);
    const auto lines = rows(file);
    for (std::size_t k = 0; k < lines.size(); ++k) {
        if (lines[k].size() != 3) {
            fail(file, "entry " + std::to_string(k + 1) + " must be 'vertex part weight'");
        }
        const auto vertex = number<long long>(file, lines[k][0], k);
        const auto part = number<int>(file, lines[k][1], k);
        const auto weight = number<double>(file, lines[k][2], k);
        if (vertex < 0 || vertex >= vertices) {
            fail(file, "entry " + std::to_string(k + 1) + ": vertex " + std::to_string(vertex) +
                           " is not in [0, " + std::to_string(vertices) + ")");
        }
        if (part < 0 || part >= parts) {
            fail(file, "entry " + std::to_string(k + 1) + ": part " + std::to_string(part) +
                           " is not in [0, " + std::to_string(parts) + ")");
        }
        weights(static_cast<Eigen::Index>(vertex), part) += weight;
    }
    return weights;
}

}  // namespace

PartModel read_part_model(const PartFiles& files, Eigen::Index vertices) {
    json document;
    try {
        document = json::parse(read_file(files.tree));
    } catch (const json::exception& e) {
        fail(files.tree, std::string("not valid JSON (") + e.what() + ")");
    }
    if (!document.is_object()) {
        fail(files.tree, "not a JSON object");
    }
    PartModel model;
    try {
        model.parts = parse_tree(files.tree, document, files);
    } catch (const json::exception& e) {
        fail(files.tree, e.what());
    }
    const auto count = static_cast<int>(model.parts.size());
    const std::filesystem::path base = files.tree.parent_path();
    std::optional<std::filesystem::path> labels = files.labels;
    std::optional<std::filesystem::path> weights = files.weights;
    if (!labels && !weights) {
        if (document.contains("labels") && document["labels"].is_string()) {
            labels = base / document["labels"].get<std::string>();
        } else if (document.contains("weights") && document["weights"].is_string()) {
            weights = base / document["weights"].get<std::string>();
        } else {
            fail(files.tree,
                 "no per-vertex part labels or weights (give a labels or weights file)");
        }
    }
    const std::filesystem::path& per_vertex = labels ? *labels : *weights;
    model.weights =
        labels ? read_labels(*labels, vertices, count) : read_weights(*weights, vertices, count);
    try {
        check_part_model(model, vertices);
    } catch (const InvalidInput& e) {
        const std::string what = e.what();
        // Tree problems belong to the JSON, weight problems to the per-vertex file.
        fail(what.find("weight") != std::string::npos ? per_vertex : files.tree, what);
    }
    return model;
}

}  // namespace genflow
