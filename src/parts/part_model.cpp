// SPDX-License-Identifier: MIT
#include "genflow/parts/part_model.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "genflow/exceptions.h"

namespace genflow {

void check_part_model(const PartModel& model, Eigen::Index vertices) {
    const auto count = static_cast<int>(model.parts.size());
    if (count == 0) {
        throw InvalidInput("part model: no parts");
    }
    int roots = 0;
    for (int p = 0; p < count; ++p) {
        const Part& part = model.parts[static_cast<std::size_t>(p)];
        if (part.parent == -1) {
            ++roots;
        } else if (part.parent < 0 || part.parent >= count || part.parent == p) {
            throw InvalidInput("part model: part '" + part.name + "' has parent " +
                               std::to_string(part.parent) + ", not a part index in [0, " +
                               std::to_string(count) + ")");
        }
        if (!part.joint_centre.allFinite()) {
            throw InvalidInput("part model: part '" + part.name +
                               "' has a non-finite joint centre");
        }
    }
    if (roots == 0) {
        throw InvalidInput(
            "part model: no root part (one without a parent): the parents form a "
            "cycle");
    }
    for (int p = 0; p < count; ++p) {  // every walk up must reach a root within `count` steps
        int at = p;
        for (int steps = 0; at != -1; ++steps) {
            if (steps > count) {
                throw InvalidInput("part model: the parents of part '" +
                                   model.parts[static_cast<std::size_t>(p)].name +
                                   "' form a cycle");
            }
            at = model.parts[static_cast<std::size_t>(at)].parent;
        }
    }
    if (model.weights.rows() != vertices || model.weights.cols() != count) {
        throw InvalidInput("part model: weights are " + std::to_string(model.weights.rows()) + "×" +
                           std::to_string(model.weights.cols()) + ", the template needs " +
                           std::to_string(vertices) + "×" + std::to_string(count) +
                           " (one row per vertex, one column per part)");
    }
    for (Eigen::Index i = 0; i < vertices; ++i) {
        double sum = 0;
        for (int p = 0; p < count; ++p) {
            const double w = model.weights(i, p);
            if (!std::isfinite(w) || w < -1e-6 || w > 1 + 1e-6) {
                throw InvalidInput("part model: vertex " + std::to_string(i) +
                                   " has a weight outside [0, 1]");
            }
            sum += w;
        }
        if (std::abs(sum - 1) > 1e-3) {
            throw InvalidInput("part model: the weights of vertex " + std::to_string(i) +
                               " sum to " + std::to_string(sum) + ", not 1");
        }
    }
}

Eigen::MatrixXd weights_from_labels(const Eigen::VectorXi& labels, int parts) {
    Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(labels.size(), parts);
    for (Eigen::Index i = 0; i < labels.size(); ++i) {
        if (labels[i] < 0 || labels[i] >= parts) {
            throw InvalidInput("part labels: vertex " + std::to_string(i) + " has label " +
                               std::to_string(labels[i]) + ", outside [0, " +
                               std::to_string(parts) + ")");
        }
        weights(i, labels[i]) = 1;
    }
    return weights;
}

PartModel restrict_to(const PartModel& model, const std::vector<Eigen::Index>& vertices) {
    PartModel restricted{model.parts, Eigen::MatrixXd(static_cast<Eigen::Index>(vertices.size()),
                                                      model.weights.cols())};
    for (std::size_t k = 0; k < vertices.size(); ++k) {
        restricted.weights.row(static_cast<Eigen::Index>(k)) = model.weights.row(vertices[k]);
    }
    return restricted;
}

std::vector<int> part_depths(const PartModel& model) {
    const auto roots = std::count_if(model.parts.begin(), model.parts.end(),
                                     [](const Part& part) { return part.parent == -1; });
    // Several roots hang from the whole template (an implicit root), one level below it.
    std::vector<int> depth(model.parts.size(), roots > 1 ? 1 : 0);
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
        for (int at = model.parts[p].parent; at != -1;
             at = model.parts[static_cast<std::size_t>(at)].parent) {
            ++depth[p];
        }
    }
    return depth;
}

}  // namespace genflow
