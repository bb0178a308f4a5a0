// SPDX-License-Identifier: MIT
#include "genflow/parts/quasi_articulated_metric.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"
#include "numerics/spd_solver.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

bool is_hard(const Eigen::MatrixXd& weights, Eigen::Index row) {
    return (weights.row(row).array() == 1).count() == 1;
}

// A joint centre bound to the mesh: Σ_k ω_k x_{vertex_k} + offset.
struct BoundJoint {
    std::vector<Eigen::Index> vertices;
    std::vector<double> omega;
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();

    [[nodiscard]] Eigen::Vector3d at(const Eigen::MatrixX3d& V) const {
        Eigen::Vector3d c = offset;
        for (std::size_t k = 0; k < vertices.size(); ++k) {
            c += omega[k] * V.row(vertices[k]).transpose();
        }
        return c;
    }
};

// The seam of a subtree weight W̃: vertices weighted by W̃(1 − W̃); without a seam (a part with
// hard weights everywhere), the 8 vertices nearest to the rest centre, by inverse distance.
BoundJoint bind_joint(const Eigen::MatrixX3d& V, const Eigen::VectorXd& subtree,
                      const Eigen::Vector3d& rest_centre) {
    BoundJoint joint;
    double total = 0;
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
        const double w = subtree[i] * (1 - subtree[i]);
        if (w > 1e-3) {
            joint.vertices.push_back(i);
            joint.omega.push_back(w);
            total += w;
        }
    }
    if (joint.vertices.empty()) {
        std::vector<std::pair<double, Eigen::Index>> nearest;
        for (Eigen::Index i = 0; i < V.rows(); ++i) {
            nearest.emplace_back((V.row(i).transpose() - rest_centre).norm(), i);
        }
        const auto k = std::min<std::size_t>(8, nearest.size());
        std::partial_sort(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(k),
                          nearest.end());
        for (std::size_t j = 0; j < k; ++j) {
            const double w = 1 / (nearest[j].first + 1e-12);
            joint.vertices.push_back(nearest[j].second);
            joint.omega.push_back(w);
            total += w;
        }
    }
    for (double& w : joint.omega) {
        w /= total;
    }
    joint.offset = rest_centre - joint.at(V);  // at() adds the offset, still zero here
    return joint;
}

}  // namespace

Eigen::MatrixXd blend_part_weights(const TriangleMesh& mesh, const Eigen::MatrixXd& weights,
                                   double blend_edges) {
    if (weights.rows() != mesh.V.rows()) {
        throw InvalidInput("blend_part_weights: one weight row per vertex is needed");
    }
    if (!detail::finite_at_least(blend_edges, 0)) {
        throw InvalidInput("blend_part_weights: blend_edges must be finite and >= 0");
    }
    if (blend_edges == 0) {
        return weights;
    }
    const double r = blend_edges * mean_edge_length(mesh);
    const Eigen::VectorXd D = lumped_masses(mesh, MassType::Barycentric);
    const double floor = 1e-10 * D.mean();
    Eigen::SparseMatrix<double> system = r * r * cotan_stiffness(mesh);
    for (Eigen::Index i = 0; i < D.size(); ++i) {
        system.coeffRef(i, i) += std::max(D[i], floor);
    }
    detail::SpdSolver solver;
    solver.compute(system, "blend_part_weights");
    const Eigen::MatrixXd rhs = D.cwiseMax(floor).asDiagonal() * weights;
    Eigen::MatrixXd blended = solver.solve(rhs).cwiseMax(0.0).cwiseMin(1.0);
    for (Eigen::Index i = 0; i < blended.rows(); ++i) {
        const double sum = blended.row(i).sum();
        if (!is_hard(weights, i)) {
            blended.row(i) = weights.row(i);  // soft weights are someone's choice: keep them
        } else if (sum > 0) {
            blended.row(i) /= sum;
        } else {
            blended.row(i) = weights.row(i);
        }
    }
    return blended;
}

SubspaceMetric quasi_articulated_metric(const TriangleMesh& rest, const PartModel& parts,
                                        const QuasiArticulatedOptions& options) {
    detail::require_valid_mesh(rest, "quasi_articulated_metric");
    check_part_model(parts, rest.V.rows());
    for (const double penalty : {options.global, options.first_level, options.deepest}) {
        if (!detail::finite_above(penalty, 0) || penalty > 1) {
            throw InvalidInput("quasi_articulated_metric: penalties must lie in (0, 1]");
        }
    }
    if (!detail::finite_at_least(options.smoothing_length, 0)) {
        throw InvalidInput("quasi_articulated_metric: smoothing_length must be finite and >= 0");
    }
    const Eigen::MatrixXd weights = blend_part_weights(rest, parts.weights, options.blend_edges);
    const auto count = static_cast<int>(parts.parts.size());
    const std::vector<int> depth = part_depths(parts);
    const int levels = *std::max_element(depth.begin(), depth.end());

    // Subtree weights W̃_k = Σ_{p ∈ subtree(k)} w_p and the bound joint of every non-root part.
    struct Limb {
        int level;
        Eigen::VectorXd subtree;
        BoundJoint joint;
    };
    auto limbs = std::make_shared<std::vector<Limb>>();
    for (int k = 0; k < count; ++k) {
        if (depth[static_cast<std::size_t>(k)] == 0) {
            continue;
        }
        Eigen::VectorXd subtree = Eigen::VectorXd::Zero(rest.V.rows());
        for (int p = 0; p < count; ++p) {
            for (int at = p; at != -1; at = parts.parts[static_cast<std::size_t>(at)].parent) {
                if (at == k) {
                    subtree += weights.col(p);
                    break;
                }
            }
        }
        BoundJoint joint =
            bind_joint(rest.V, subtree, parts.parts[static_cast<std::size_t>(k)].joint_centre);
        limbs->push_back(
            {depth[static_cast<std::size_t>(k)], std::move(subtree), std::move(joint)});
    }

    const QuasiRigidOptions global{.translation = options.global,
                                   .rotation = options.global,
                                   .scaling = std::min(1.0, 10 * options.global),
                                   .mass = options.mass};
    auto basis = [limbs, levels, global, options](const TriangleMesh& mesh,
                                                  const Eigen::VectorXd& masses) {
        std::vector<FieldBlock> blocks = rigid_motion_blocks(mesh, masses, global);
        for (int level = 1; level <= levels; ++level) {
            const double penalty =
                std::min(options.deepest, options.first_level * std::pow(10.0, level - 1));
            std::vector<const Limb*> at_level;
            for (const Limb& limb : *limbs) {
                if (limb.level == level) {
                    at_level.push_back(&limb);
                }
            }
            FieldBlock block{Eigen::MatrixXd::Zero(3 * mesh.V.rows(),
                                                   3 * static_cast<Eigen::Index>(at_level.size())),
                             penalty};
            for (std::size_t k = 0; k < at_level.size(); ++k) {
                const Eigen::Vector3d centre = at_level[k]->joint.at(mesh.V);
                const auto column = static_cast<Eigen::Index>(3 * k);
                for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
                    const double w = at_level[k]->subtree[i];
                    if (w == 0) {
                        continue;
                    }
                    const Eigen::Vector3d y = w * (mesh.V.row(i).transpose() - centre);
                    // Column a: w·e_a × (x − c).
                    block.fields.block<3, 3>(3 * i, column) << 0, y.z(), -y.y(),  //
                        -y.z(), 0, y.x(),                                         //
                        y.y(), -y.x(), 0;
                }
            }
            blocks.push_back(std::move(block));
        }
        return blocks;
    };
    std::unique_ptr<Metric> base;
    if (options.smoothing_length > 0) {
        const double length = options.smoothing_length * mean_edge_length(rest);
        base = std::make_unique<H1Metric>(SobolevOptions{.lambda = length * length});
    }
    return SubspaceMetric(basis, {options.mass}, std::move(base));
}

}  // namespace genflow
