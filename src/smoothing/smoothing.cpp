// SPDX-License-Identifier: MIT
#include "genflow/smoothing/smoothing.h"

#include <cmath>
#include <limits>
#include <string>

#include "genflow/energies/surface_area_energy.h"
#include "genflow/exceptions.h"
#include "genflow/flows/explicit_euler.h"
#include "genflow/flows/implicit_euler.h"
#include "genflow/mesh/edges.h"
#include "genflow/metrics/l2_metric.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/metrics/volume_controlled_metric.h"
#include "genflow/operators/area.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

// Checks the mesh and options once and returns the mean edge length h. What a flow cannot
// start from is checked (validate()'s errors): not the topology, whose findings are warnings,
// and whose sorting of every edge cost as much as two fairing steps.
double prepare(const TriangleMesh& mesh, const SmoothingOptions& options, const char* caller) {
    detail::require_valid_mesh(mesh, caller);
    if (mesh.F.rows() == 0) {
        throw InvalidInput(std::string(caller) + ": mesh has no faces");
    }
    if (!(surface_area(mesh) > 0)) {
        throw InvalidInput(std::string(caller) + ": every face has zero area");
    }
    if (!detail::finite_above(options.time_step, 0) || options.steps < 0) {
        throw InvalidInput(std::string(caller) +
                           ": need a positive finite time_step and steps >= 0");
    }
    const double h = mean_edge_length(mesh);
    if (!detail::finite_above(h, 0)) {
        throw InvalidInput(std::string(caller) + ": mesh has no edge of positive length");
    }
    return h;
}

double metric_lambda(const SmoothingOptions& options, double h, double time_step) {
    return options.lambda ? *options.lambda * h * h : time_step;
}

FlowOptions flow_options(const SmoothingOptions& options, double time_step) {
    FlowOptions flow;
    flow.time_step = time_step;
    flow.max_steps = options.steps;
    flow.progress = options.progress;
    return flow;
}

// A metric evaluated at the flow's first mesh and kept (SmoothingOptions::freeze_metric).
class FrozenMetric final : public Metric {
public:
    explicit FrozenMetric(Metric& metric) : metric_(metric) {}

    void update(const TriangleMesh& mesh) override {
        if (!updated_) {
            metric_.update(mesh);
            updated_ = true;
        }
    }
    void update_alongside(const TriangleMesh& mesh, const std::function<void()>& task) override {
        if (!updated_) {
            metric_.update_alongside(mesh, task);
            updated_ = true;
        } else if (task) {
            task();
        }
    }
    [[nodiscard]] VertexField gradient(const VertexField& dEdX) const override {
        return metric_.gradient(dEdX);
    }
    [[nodiscard]] VertexField apply(const VertexField& U) const override {
        return metric_.apply(U);
    }
    [[nodiscard]] VertexField shifted_gradient(const Eigen::SparseMatrix<double>& A, double dt,
                                               const VertexField& R) override {
        return metric_.shifted_gradient(A, dt, R);
    }

private:
    Metric& metric_;
    bool updated_ = false;
};

enum class Integrator { Explicit, Implicit };

FlowResult area_flow(const TriangleMesh& mesh, const SmoothingOptions& options, Metric& metric,
                     double time_step, Integrator integrator = Integrator::Explicit) {
    if (options.fix_boundary) {
        metric.set_fixed_vertices(boundary_vertices(mesh.F, mesh.V.rows()));
    }
    const FlowOptions flow = flow_options(options, time_step);
    FrozenMetric frozen(metric);
    Metric& used = options.freeze_metric ? static_cast<Metric&>(frozen) : metric;
    return integrator == Integrator::Explicit
               ? explicit_euler(mesh, SurfaceAreaEnergy{}, used, flow)
               : implicit_euler(mesh, SurfaceAreaEnergy{}, used, flow);
}

// A smoothing flow has the machine to itself: factorizations in two halves side by side, each
// supernodal where its factor is dense enough for the BLAS to pay (twice as fast as simplicial
// on the 48K horse), simplicial below (docs/benchmarks.md, "By flop density", "Two halves").
// A metric updated at every step is factored for each step's solve or few, so with wide
// supernodes from the first analysis; a frozen one, factored once and solved at every step,
// with narrow ones.
Factorization smoothing_factorization(const SmoothingOptions& options) {
    return options.freeze_metric ? Factorization::ByFlopDensity : Factorization::ByFlopDensityWide;
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
    H1Metric metric({.lambda = metric_lambda(options, h, time_step),
                     .factorization = smoothing_factorization(options)});
    return area_flow(mesh, options, metric, time_step);
}

FlowResult higher_order_fairing(const TriangleMesh& mesh, const SmoothingOptions& options) {
    const double h = prepare(mesh, options, "higher_order_fairing");
    if (!detail::finite_at_least(options.mu, 0)) {
        throw InvalidInput("higher_order_fairing: mu must be non-negative and finite");
    }
    const double time_step = options.time_step * h * h;
    H2Metric metric({.lambda = metric_lambda(options, h, time_step),
                     .mu = options.mu * h * h * h * h,
                     .factorization = smoothing_factorization(options)});
    return area_flow(mesh, options, metric, time_step);
}

// The relative residual of volume-controlled fairing's implicit solves. After ten steps on the
// noisy horse, stopping at 1e-4 moves the vertices from where an exact solve (1e-10) puts them
// by 5e-5 of how far they moved (1e-6: 2e-7; 1e-3: 4.5e-4), far below the implicit Euler step's
// own error, and takes 5 GMRES iterations a step where 1e-6 takes 8 and 1e-10 12
// (docs/benchmarks.md, "Volume-controlled fairing, the normal speeds alone").
constexpr double kFairingSolveTolerance = 1e-4;

FlowResult volume_controlled_fairing(const TriangleMesh& mesh, const SmoothingOptions& options) {
    const double h = prepare(mesh, options, "volume_controlled_fairing");
    VolumeControlledMetric metric({.lambda = options.volume_lambda,
                                   .tolerance = kFairingSolveTolerance,
                                   .factorization = smoothing_factorization(options)});
    return area_flow(mesh, options, metric, options.time_step * h * h, Integrator::Implicit);
}

const std::vector<SmoothingFlow>& smoothing_flows() {
    static const std::vector<SmoothingFlow> flows = {
        {"mcf", &mean_curvature_flow},
        {"fairing", &implicit_fairing},
        {"fairing2", &higher_order_fairing},
        {"volume-fairing", &volume_controlled_fairing},
    };
    return flows;
}

const SmoothingFlow& smoothing_flow(std::string_view name) {
    std::string names;
    for (const SmoothingFlow& flow : smoothing_flows()) {
        if (flow.name == name) {
            return flow;
        }
        names += std::string(names.empty() ? "'" : ", '") + std::string(flow.name) + "'";
    }
    throw InvalidInput("smooth: method must be one of " + names + ", got '" + std::string(name) +
                       "'");
}

}  // namespace genflow
