// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace genflow {

/// A part of an articulated template: its name, its parent in the part tree (−1 for a root)
/// and the rest position of the joint that links it to its parent (for the only root: any
/// point, unused; where several parts are roots, the joint each turns about).
struct Part {
    std::string name;
    int parent = -1;
    Eigen::Vector3d joint_centre = Eigen::Vector3d::Zero();
};

/// The parts of a template for the quasi-articulated prior (paper §6.3.2): a tree of parts and
/// per-vertex part weights (one row per template vertex, one column per part, non-negative,
/// rows summing to 1; hard labels are rows with a single 1).
struct PartModel {
    std::vector<Part> parts;
    Eigen::MatrixXd weights;
};

/// Throws InvalidInput with a one-line reason unless `model` fits a template of `vertices`
/// vertices: at least one part, at least one root, parents in range and no cycle, finite joint
/// centres, one weight row per vertex, weights finite, in [0, 1] (to 1e-6) and summing to 1
/// (to 1e-3).
void check_part_model(const PartModel& model, Eigen::Index vertices);

/// Part weights from one label per vertex (0-based part indices): rows with a single 1.
/// \throws InvalidInput if a label is outside [0, parts).
[[nodiscard]] Eigen::MatrixXd weights_from_labels(const Eigen::VectorXi& labels, int parts);

/// The model restricted to some vertices (a coarse level whose vertex k is template vertex
/// `vertices[k]`).
[[nodiscard]] PartModel restrict_to(const PartModel& model,
                                    const std::vector<Eigen::Index>& vertices);

/// Depth of each part in the tree: 0 for the root, whose motion is the whole template's. A
/// forest (several roots, as a skeleton whose root joint has several bones: the libigl
/// elephant's hips) hangs from the whole template, its roots at depth 1, each turning about its
/// own joint centre. Assumes a model that passed check_part_model().
[[nodiscard]] std::vector<int> part_depths(const PartModel& model);

}  // namespace genflow
