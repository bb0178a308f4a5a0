// SPDX-License-Identifier: MIT
#include "matching/level_flow.h"

#include <memory>
#include <optional>
#include <utility>

#include "genflow/energies/edge_length_energy.h"
#include "genflow/energies/landmark_energy.h"
#include "genflow/energies/weighted_sum_energy.h"
#include "genflow/exceptions.h"
#include "genflow/flows/gradient_descent.h"
#include "genflow/metrics/l2_metric.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/parts/quasi_articulated_metric.h"
#include "matching/partial_target.h"

namespace genflow::detail {

namespace {

// `parts`: the level's part model, joint centres at the positions of `template_mesh`;
// `articulated`: the articulated prior's options at this level.
std::unique_ptr<Metric> make_metric(const MatchOptions& options, MatchPrior prior,
                                    const TriangleMesh& template_mesh, const PartModel* parts,
                                    const QuasiArticulatedOptions& articulated) {
    switch (prior) {
        case MatchPrior::L2:
            return std::make_unique<L2Metric>();
        case MatchPrior::H1: {
            const double length = options.h1_length * mean_edge_length(template_mesh);
            return std::make_unique<H1Metric>(SobolevOptions{.lambda = length * length});
        }
        case MatchPrior::Rigid:
            return std::make_unique<SubspaceMetric>(quasi_rigid_metric(options.rigid));
        case MatchPrior::Articulated:
            return std::make_unique<SubspaceMetric>(
                quasi_articulated_metric(template_mesh, *parts, articulated));
        case MatchPrior::Isometric:
            return std::make_unique<QuasiIsometricMetric>(options.isometric);
    }
    throw InvalidInput("match: unknown prior");
}

// The landmarks on level `l`'s template: each on its own vertex where the level keeps it, else
// on the level's vertex nearest to it at rest (a coarse level keeps a subset of the vertices).
std::shared_ptr<const LandmarkEnergy> level_landmarks(const std::vector<Level>& pyramid, int l,
                                                      const std::vector<Landmark>& landmarks,
                                                      double diagonal) {
    const Level& level = pyramid[static_cast<std::size_t>(l)];
    const Eigen::MatrixX3d& finest_rest = pyramid.front().template_mesh.V;
    std::vector<Eigen::Index> vertices;
    Eigen::MatrixX3d points(static_cast<Eigen::Index>(landmarks.size()), 3);
    Eigen::VectorXd weights(static_cast<Eigen::Index>(landmarks.size()));
    for (std::size_t k = 0; k < landmarks.size(); ++k) {
        Eigen::Index nearest = 0;
        (level.template_mesh.V.rowwise() - finest_rest.row(landmarks[k].vertex))
            .rowwise()
            .squaredNorm()
            .minCoeff(&nearest);
        vertices.push_back(nearest);
        points.row(static_cast<Eigen::Index>(k)) = landmarks[k].target_point.transpose();
        weights[static_cast<Eigen::Index>(k)] = landmarks[k].weight;
    }
    return std::make_shared<const LandmarkEnergy>(level.template_mesh.V.rows(), std::move(vertices),
                                                  std::move(points), diagonal, std::move(weights));
}

}  // namespace

PseudoHausdorffEnergy LevelFlows::distance_to_target(const Level& level, double epsilon_factor,
                                                     const PointDescriptors& descriptors) const {
    return PseudoHausdorffEnergy(level.target,
                                 {.alpha = options_.alpha,
                                  .epsilon = epsilon_factor * mean_edge_length(level.target),
                                  .truncation = options_.truncation,
                                  .moving_coverage = matches_partial_target(options_) ? 0.0 : 1.0},
                                 descriptors);
}

FlowResult LevelFlows::flow(int l, const TriangleMesh& moved, int iterations,
                            const Similarity& placement, MatchPrior prior,
                            const PointDescriptors& descriptors, double stretch_weight,
                            bool reports) const {
    if (memo_ == nullptr || l != coarsest()) {
        return run_flow(l, moved, iterations, placement, prior, descriptors, stretch_weight,
                        reports);
    }
    const FlowRequest request{l,     &moved.V,     iterations,    &placement,
                              prior, &descriptors, stretch_weight};
    if (std::optional<FlowResult> seen = memo_->find(request)) {
        return std::move(*seen);
    }
    FlowResult result =
        run_flow(l, moved, iterations, placement, prior, descriptors, stretch_weight, reports);
    if (!cancelled_) {  // a cancelled flow stopped short
        memo_->keep(request, result);
    }
    return result;
}

FlowResult LevelFlows::run_flow(int l, const TriangleMesh& moved, int iterations,
                                const Similarity& placement, MatchPrior prior,
                                const PointDescriptors& descriptors, double stretch_weight,
                                bool reports) const {
    const Level& level = pyramid_[static_cast<std::size_t>(l)];
    std::optional<PartModel> parts;
    if (options_.parts) {  // this level's weights, joints moved with the template
        parts = restrict_to(*options_.parts, level.original_vertex);
        for (Part& part : parts->parts) {
            part.joint_centre = placement.apply(part.joint_centre.transpose()).transpose();
        }
    }
    const TriangleMesh rest = placed_template(level, placement);  // the joint centres' frame
    std::shared_ptr<const EdgeLengthEnergy> stretch;
    if (stretch_weight > 0) {
        stretch = std::make_shared<EdgeLengthEnergy>(rest);
    }
    std::shared_ptr<const LandmarkEnergy> landmarks;
    if (!options_.landmarks.points.empty() && options_.landmarks.weight > 0) {
        landmarks = level_landmarks(pyramid_, l, options_.landmarks.points, diagonal_);
    }
    const auto energy_with_epsilon = [&](double epsilon_factor) {
        std::vector<WeightedSumEnergy::Term> terms{
            {1.0, std::make_shared<const PseudoHausdorffEnergy>(
                      distance_to_target(level, epsilon_factor, descriptors))}};
        if (stretch) {
            terms.push_back({stretch_weight * diagonal_, stretch});
        }
        if (landmarks) {
            terms.push_back({options_.landmarks.weight * diagonal_, landmarks});
        }
        return WeightedSumEnergy(std::move(terms));
    };
    const WeightedSumEnergy energy = energy_with_epsilon(1);
    QuasiArticulatedOptions articulated = options_.articulated;
    if (l == 0 && count() > 1) {  // the finest of several levels
        articulated.global = options_.articulated_finest_global;
    }
    const std::unique_ptr<Metric> metric =
        make_metric(options_, prior, rest, parts ? &*parts : nullptr, articulated);
    DescentOptions descent{.max_displacement = options_.max_step * diagonal_,
                           .max_steps = iterations,
                           .stagnation_tolerance = options_.stagnation_tolerance,
                           .stagnation_window = 20,
                           .implicit = options_.implicit,
                           .first_step = options_.first_step,
                           .quasi_newton_memory = options_.quasi_newton_memory};
    if (options_.progress && reports) {
        descent.progress = [this, l](const FlowProgress& p) {
            const bool go_on =
                options_.progress({l, count(), p.step, p.max_steps, p.energy, p.mesh,
                                   &pyramid_[static_cast<std::size_t>(l)].original_vertex});
            if (!go_on) {
                cancelled_ = true;
            }
            return go_on;
        };
    } else if (options_.progress) {
        descent.progress = [this](const FlowProgress&) { return !cancelled_; };
    }
    if (l == count() - 1 && options_.coarse_epsilon != 1) {
        // First half with the smoother d_H of a larger ε, then the level's own ε; the
        // energies reported are all of the latter.
        descent.max_steps = iterations / 2;
        const FlowResult smooth =
            gradient_descent(moved, energy_with_epsilon(options_.coarse_epsilon), *metric, descent);
        descent.max_steps = iterations - smooth.steps;
        FlowResult flow = gradient_descent(smooth.mesh, energy, *metric, descent);
        flow.steps += smooth.steps;
        flow.energy.insert(flow.energy.begin(), energy.value(moved));
        return flow;
    }
    return gradient_descent(moved, energy, *metric, descent);
}

void LevelFlows::tell(int l, std::string_view stage, const TriangleMesh& mesh) const {
    if (options_.stages) {
        const Level& level = pyramid_[static_cast<std::size_t>(l)];
        options_.stages({l, count(), stage, &mesh, &level.original_vertex});
    }
}

MatchLevel level_report(const Level& level, const FlowResult& flow, double seconds) {
    return MatchLevel{flow.mesh.V.rows(),  level.target.V.rows(), flow.steps, flow.status,
                      flow.energy.front(), flow.energy.back(),    seconds,    flow.energy};
}

}  // namespace genflow::detail
