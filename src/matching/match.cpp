// SPDX-License-Identifier: MIT
#include "genflow/matching/match.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/exceptions.h"
#include "genflow/flows/gradient_descent.h"
#include "genflow/metrics/l2_metric.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/operators/mesh_size.h"
#include "operators/triangle.h"

namespace genflow {

const char* to_string(MatchPrior prior) {
    switch (prior) {
        case MatchPrior::L2:
            return "l2";
        case MatchPrior::H1:
            return "h1";
        case MatchPrior::Rigid:
            return "rigid";
    }
    return "unknown";
}

std::optional<MatchPrior> parse_match_prior(const std::string& name) {
    for (const MatchPrior prior : {MatchPrior::L2, MatchPrior::H1, MatchPrior::Rigid}) {
        if (name == to_string(prior)) {
            return prior;
        }
    }
    return std::nullopt;
}

namespace {

void check_inputs(const TriangleMesh& template_mesh, const TriangleMesh& target,
                  const MatchOptions& options) {
    for (const auto& [mesh, name] : {std::pair{&template_mesh, "template"}, {&target, "target"}}) {
        detail::require_valid_mesh(*mesh, "match");
        if (mesh->F.rows() == 0) {
            throw InvalidInput(std::string("match: the ") + name + " has no faces");
        }
        if (!(bounding_box_diagonal(*mesh) > 0)) {
            throw InvalidInput(std::string("match: the ") + name + " has zero extent");
        }
    }
    if (options.max_iterations < 0 || !detail::finite_above(options.max_step, 0) ||
        !detail::finite_at_least(options.stagnation_tolerance, 0) ||
        options.alignment_candidates < 1 || !detail::finite_above(options.h1_length, 0)) {
        throw InvalidInput(
            "match: need max_iterations >= 0, max_step > 0, stagnation_tolerance >= 0, "
            "alignment_candidates >= 1 and h1_length > 0");
    }
}

std::unique_ptr<Metric> make_metric(const MatchOptions& options, const TriangleMesh& template_mesh) {
    switch (options.prior) {
        case MatchPrior::L2:
            return std::make_unique<L2Metric>();
        case MatchPrior::H1: {
            const double length = options.h1_length * mean_edge_length(template_mesh);
            return std::make_unique<H1Metric>(SobolevOptions{.lambda = length * length});
        }
        case MatchPrior::Rigid:
            return std::make_unique<SubspaceMetric>(quasi_rigid_metric(options.rigid));
    }
    throw InvalidInput("match: unknown prior");
}

}  // namespace

MatchResult match(const TriangleMesh& template_mesh, const TriangleMesh& target,
                  const MatchOptions& options) {
    check_inputs(template_mesh, target, options);
    const PseudoHausdorffEnergy energy(
        target, {.alpha = options.alpha,
                 .epsilon = mean_edge_length(target),
                 .truncation = options.truncation});
    const double diagonal = bounding_box_diagonal(target);

    MatchResult result;
    std::vector<Similarity> starts{Similarity{}};
    auto clock = std::chrono::steady_clock::now();
    const auto seconds_since = [](std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    };
    if (options.align) {
        RigidAlignmentOptions alignment = options.alignment;
        alignment.best_starts = std::max(alignment.best_starts, options.alignment_candidates);
        starts.clear();
        for (const RigidAlignment& candidate :
             rigid_alignment_candidates(template_mesh, target, alignment)) {
            starts.push_back(candidate.transform);
            if (static_cast<int>(starts.size()) == options.alignment_candidates) {
                break;
            }
        }
    }
    result.alignment_seconds = seconds_since(clock);

    clock = std::chrono::steady_clock::now();
    bool first = true;
    for (const Similarity& start : starts) {
        TriangleMesh moved = template_mesh;
        moved.V = start.apply(template_mesh.V);
        const std::unique_ptr<Metric> metric = make_metric(options, moved);
        DescentOptions descent{.max_displacement = options.max_step * diagonal,
                               .max_steps = options.max_iterations,
                               .stagnation_tolerance = options.stagnation_tolerance,
                               .stagnation_window = 20};
        if (options.progress) {
            descent.progress = [&](const FlowProgress& p) {
                return options.progress(
                    {to_string(options.prior), p.step, p.max_steps, p.energy, p.mesh});
            };
        }
        FlowResult flow = gradient_descent(moved, energy, *metric, descent);
        const double value = flow.energy.back();
        if (first || value < result.hausdorff_energy) {
            result.deformed = std::move(flow.mesh);
            result.initial_alignment = start;
            result.iterations = flow.steps;
            result.status = flow.status;
            result.hausdorff_energy = value;
            result.energy = std::move(flow.energy);
        }
        first = false;
        if (flow.status == FlowStatus::Cancelled) {
            break;
        }
    }
    result.flow_seconds = seconds_since(clock);
    return result;
}

}  // namespace genflow
