// SPDX-License-Identifier: MIT
#include "genflow/smoothing/smoothing.h"

#include <cmath>
#include <limits>
#include <string>

#include "genflow/energies/surface_area_energy.h"
#include "genflow/exceptions.h"
#include "genflow/flows/explicit_euler.h"
#include "genflow/mesh/validate.h"
#include "genflow/metrics/l2_metric.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"

namespace genflow {

namespace {

// Checks the mesh and options once and returns the mean edge length h.
double prepare(const TriangleMesh& mesh, const SmoothingOptions& options, const char* caller) {
    const ValidationReport report = validate(mesh);
    if (!report.ok()) {
        throw InvalidInput(std::string(caller) + ": " + report.first_error());
    }
    if (!(options.time_step > 0) || !std::isfinite(options.time_step) || options.steps < 0) {
        throw InvalidInput(std::string(caller) +
                           ": need a positive finite time_step and steps >= 0");
    }
    const double h = mean_edge_length(mesh);
    if (!(h > 0)) {
        throw InvalidInput(std::string(caller) + ": mesh has no edge of positive length");
    }
    return h;
}

std::vector<bool> boundary_mask(const TriangleMesh& mesh) {
    // An edge used by exactly one face is a boundary edge; its vertices are boundary vertices.
    std::vector<std::pair<int, int>> edges;
    edges.reserve(static_cast<std::size_t>(3 * mesh.F.rows()));
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            const int a = mesh.F(f, k);
            const int b = mesh.F(f, (k + 1) % 3);
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    }
    std::sort(edges.begin(), edges.end());
    std::vector<bool> fixed(static_cast<std::size_t>(mesh.V.rows()), false);
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) {
            ++j;
        }
        if (j - i == 1) {
            fixed[static_cast<std::size_t>(edges[i].first)] = true;
            fixed[static_cast<std::size_t>(edges[i].second)] = true;
        }
        i = j;
    }
    return fixed;
}

FlowOptions flow_options(const SmoothingOptions& options, double time_step) {
    FlowOptions flow;
    flow.time_step = time_step;
    flow.max_steps = options.steps;
    flow.progress = options.progress;
    return flow;
}

FlowResult area_flow(const TriangleMesh& mesh, const SmoothingOptions& options, Metric& metric,
                     double time_step) {
    if (options.fix_boundary) {
        metric.set_fixed_vertices(boundary_mask(mesh));
    }
    return explicit_euler(mesh, SurfaceAreaEnergy{}, metric, flow_options(options, time_step));
}

}  // namespace

FlowResult mean_curvature_flow(const TriangleMesh& mesh, const SmoothingOptions& options) {
    const double h = prepare(mesh, options, "mean_curvature_flow");
    // Explicit Euler is stable for dt < 2/λ_max(D⁻¹K); by Gershgorin on the rows of D⁻¹K,
    // λ_max ≤ max_i Σ_j |K_ij| / m_i.
    const Eigen::SparseMatrix<double> K = cotan_stiffness(mesh);
    const Eigen::VectorXd m = lumped_masses(mesh, MassType::Voronoi);
    Eigen::VectorXd row_sums = Eigen::VectorXd::Zero(m.size());
    for (Eigen::Index col = 0; col < K.outerSize(); ++col) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(K, col); it; ++it) {
            row_sums[it.row()] += std::abs(it.value());
        }
    }
    double limit = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < m.size(); ++i) {
        if (row_sums[i] > 0 && m[i] > 0) {
            limit = std::min(limit, 2 * m[i] / row_sums[i]);
        }
    }
    const double time_step = std::min(options.time_step * h * h, 0.9 * limit);
    L2Metric metric({.mass = MassType::Voronoi});
    return area_flow(mesh, options, metric, time_step);
}

FlowResult implicit_fairing(const TriangleMesh& mesh, const SmoothingOptions& options) {
    const double h = prepare(mesh, options, "implicit_fairing");
    const double time_step = options.time_step * h * h;
    H1Metric metric({.lambda = time_step});
    return area_flow(mesh, options, metric, time_step);
}

FlowResult higher_order_fairing(const TriangleMesh& mesh, const SmoothingOptions& options) {
    const double h = prepare(mesh, options, "higher_order_fairing");
    if (!(options.mu >= 0) || !std::isfinite(options.mu)) {
        throw InvalidInput("higher_order_fairing: mu must be non-negative and finite");
    }
    const double time_step = options.time_step * h * h;
    H2Metric metric({.lambda = time_step, .mu = options.mu * h * h * h * h});
    return area_flow(mesh, options, metric, time_step);
}

}  // namespace genflow
