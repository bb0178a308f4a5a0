// SPDX-License-Identifier: MIT
#include "genflow/energies/pseudo_hausdorff_energy.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "genflow/exceptions.h"
#include "genflow/operators/mass_matrix.h"
#include "operators/triangle.h"
#include "spatial/point_index.h"

namespace genflow {

namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();
// Below this many points a thread team costs more than it saves.
constexpr Eigen::Index kParallelThreshold = 2000;

int thread_count() {
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

int thread_id() {
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

// log Σ exp(v) over the finite entries; −inf if there is none.
double log_sum_exp(const std::vector<double>& values) {
    double largest = kMinusInfinity;
    for (const double v : values) {
        largest = std::max(largest, v);
    }
    if (largest == kMinusInfinity) {
        return kMinusInfinity;
    }
    double sum = 0;
    for (const double v : values) {
        sum += std::exp(v - largest);
    }
    return largest + std::log(sum);
}

// r^α for 0 < r ≤ 1, by repeated squaring when α is a small integer (the usual 8 or 16).
double ratio_power(double r, double alpha, int integer_alpha) {
    if (integer_alpha > 0) {
        double result = 1;
        double base = r;
        for (int e = integer_alpha; e > 0; e >>= 1) {
            if (e & 1) {
                result *= base;
            }
            base *= base;
        }
        return result;
    }
    return std::pow(r, alpha);
}

// One point set of the distance: positions and log weights, with the positive-weight points
// ("active") indexed for neighbour queries.
struct Side {
    Eigen::MatrixX3d points;
    Eigen::VectorXd log_weight;         // −inf for zero-mass vertices
    Eigen::VectorXd weight;             // exp(log_weight), kept to spare an exp per pair
    std::vector<std::uint32_t> active;  // vertices with positive weight
    double total_weight = 0;
    std::unique_ptr<detail::PointIndex> index;  // over `active`, only when truncating

    Side(const Eigen::MatrixX3d& positions, const Eigen::VectorXd& masses, HausdorffWeights weights,
         bool build_index)
        : points(positions) {
        const double normalizer =
            weights == HausdorffWeights::Paper ? static_cast<double>(masses.size()) : masses.sum();
        log_weight.resize(masses.size());
        weight = Eigen::VectorXd::Zero(masses.size());
        Eigen::MatrixX3d active_points(masses.size(), 3);
        for (Eigen::Index i = 0; i < masses.size(); ++i) {
            if (masses[i] > 0) {
                log_weight[i] = std::log(masses[i] / normalizer);
                weight[i] = masses[i] / normalizer;
                total_weight += masses[i] / normalizer;
                active_points.row(static_cast<Eigen::Index>(active.size())) = points.row(i);
                active.push_back(static_cast<std::uint32_t>(i));
            } else {
                log_weight[i] = kMinusInfinity;
            }
        }
        if (build_index) {
            index = std::make_unique<detail::PointIndex>(
                active_points.topRows(static_cast<Eigen::Index>(active.size())));
        }
    }
};

// A kept term of f_u = Σ_w weight_w d_uw^{−α}: the other point, d_uw, and its share
// weight_w d_uw^{−α} / f_u ∈ (0, 1].
struct Term {
    std::uint32_t other;
    double d;
    double share;
};

struct Sums {
    Eigen::VectorXd log_sum;               // log f_u (−inf for inactive u)
    std::vector<std::vector<Term>> terms;  // per u, when truncating and within the budget
    std::vector<double> radius2;           // per u, when truncating: the search radius²
    std::vector<char> stored;              // per u: are its terms in `terms`?
    std::size_t pairs = 0;
};

struct Parameters {
    double alpha;
    int integer_alpha;  // α when it is an integer in [1, 64], else 0
    double eps2;
    double truncation;
    std::size_t stored_term_budget;
};

// f_u = Σ_{w ∈ to} weight_w d_uw^{−α} for every u of `from`, scaled by the nearest term so that
// nothing overflows: f_u = d*^{−α} Σ_w weight_w (d*/d_uw)^α with d* the smallest d_uw.
Sums sum_over(const Side& from, const Side& to, const Parameters& p) {
    const auto count = static_cast<Eigen::Index>(from.points.rows());
    Sums sums;
    sums.log_sum = Eigen::VectorXd::Constant(count, kMinusInfinity);
    const bool truncate = p.truncation > 0;
    if (truncate) {
        sums.terms.resize(static_cast<std::size_t>(count));
        sums.radius2.assign(static_cast<std::size_t>(count), 0.0);
        sums.stored.assign(static_cast<std::size_t>(count), 0);
    }
    std::atomic<std::size_t> stored_terms{0};
    std::size_t pairs = 0;
#pragma omp parallel reduction(+ : pairs) if (count > kParallelThreshold)
    {
        std::vector<std::pair<std::uint32_t, double>> found;
#pragma omp for schedule(dynamic, 128)
        for (Eigen::Index u = 0; u < count; ++u) {
            if (from.log_weight[u] == kMinusInfinity || to.active.empty()) {
                continue;
            }
            const Eigen::Vector3d x = from.points.row(u).transpose();
            if (truncate) {
                // Adaptive radius (SPEC.md §8): with the nearest term weight_n d*^{−α} ≤ f_u,
                // everything beyond d = κ² d* adds at most W (κ² d*)^{−α} ≤ τ f_u when
                // κ² = (W/(weight_n τ))^{1/α}.
                const auto [nearest, rho2] = to.index->nearest(x);
                const double d_star = rho2 + p.eps2;
                const double log_w_nearest =
                    to.log_weight[to.active[static_cast<std::size_t>(nearest)]];
                const double kappa2 = std::exp(
                    (std::log(to.total_weight) - log_w_nearest - std::log(p.truncation)) / p.alpha);
                const double radius2 = kappa2 * d_star - p.eps2;
                to.index->within(x, radius2 * (1 + 1e-12), found);
                sums.radius2[static_cast<std::size_t>(u)] = radius2 * (1 + 1e-12);
                const bool store =
                    stored_terms.fetch_add(found.size()) + found.size() <= p.stored_term_budget;
                sums.stored[static_cast<std::size_t>(u)] = store ? 1 : 0;
                double sum = 0;
                auto& terms = sums.terms[static_cast<std::size_t>(u)];
                terms.clear();
                if (store) {
                    terms.reserve(found.size());
                }
                for (const auto& [local, dist2] : found) {
                    const std::uint32_t w = to.active[local];
                    const double d = dist2 + p.eps2;
                    const double share =
                        to.weight[w] * ratio_power(d_star / d, p.alpha, p.integer_alpha);
                    sum += share;
                    if (store) {
                        terms.push_back({w, d, share});
                    }
                }
                for (auto& term : terms) {
                    term.share /= sum;
                }
                sums.log_sum[u] = std::log(sum) - p.alpha * std::log(d_star);
                pairs += found.size();
            } else {
                double d_star = std::numeric_limits<double>::infinity();
                for (const std::uint32_t w : to.active) {
                    d_star =
                        std::min(d_star, (to.points.row(w).transpose() - x).squaredNorm() + p.eps2);
                }
                double sum = 0;
                for (const std::uint32_t w : to.active) {
                    const double d = (to.points.row(w).transpose() - x).squaredNorm() + p.eps2;
                    sum += to.weight[w] * ratio_power(d_star / d, p.alpha, p.integer_alpha);
                }
                sums.log_sum[u] = std::log(sum) - p.alpha * std::log(d_star);
                pairs += to.active.size();
            }
        }
    }
    sums.pairs = pairs;
    return sums;
}

// Calls visit(other, d, share) for every term of f_u: the stored ones, the kept ones found
// again, or (without truncation) all of them. `found` is the caller's scratch buffer.
template <typename Visit>
void for_each_term(const Side& from, const Side& to, const Sums& sums, const Parameters& p,
                   Eigen::Index u, std::vector<std::pair<std::uint32_t, double>>& found,
                   Visit&& visit) {
    const auto k = static_cast<std::size_t>(u);
    if (!sums.stored.empty() && sums.stored[k]) {
        for (const Term& term : sums.terms[k]) {
            visit(term.other, term.d, term.share);
        }
        return;
    }
    const Eigen::Vector3d x = from.points.row(u).transpose();
    const auto visit_one = [&](std::uint32_t w, double d) {
        visit(w, d, std::exp(to.log_weight[w] - p.alpha * std::log(d) - sums.log_sum[u]));
    };
    if (!sums.radius2.empty()) {
        to.index->within(x, sums.radius2[k], found);
        for (const auto& [local, dist2] : found) {
            visit_one(to.active[local], dist2 + p.eps2);
        }
        return;
    }
    for (const std::uint32_t w : to.active) {
        visit_one(w, (to.points.row(w).transpose() - x).squaredNorm() + p.eps2);
    }
}

}  // namespace

namespace {

void check_options(const PseudoHausdorffOptions& options, const char* caller) {
    if (!detail::finite_at_least(options.alpha, 0.5)) {
        throw InvalidInput(std::string(caller) + ": alpha must be finite and >= 0.5, got " +
                           std::to_string(options.alpha));
    }
    if (!detail::finite_above(options.epsilon, 0)) {
        throw InvalidInput(std::string(caller) + ": epsilon must be positive and finite, got " +
                           std::to_string(options.epsilon));
    }
    if (!detail::finite_at_least(options.truncation, 0) || options.truncation >= 0.5) {
        throw InvalidInput(std::string(caller) + ": truncation must lie in [0, 0.5), got " +
                           std::to_string(options.truncation));
    }
}

}  // namespace

struct PseudoHausdorffEnergy::Impl {
    Side target;
    std::mutex cache_mutex;
    Eigen::MatrixX3d cached_V;
    Eigen::MatrixX3i cached_F;
    std::shared_ptr<const PseudoHausdorffEvaluation> cached;

    Impl(const TriangleMesh& mesh, const PseudoHausdorffOptions& options)
        : target(mesh.V, lumped_masses(mesh, MassType::Barycentric), options.weights,
                 options.truncation > 0) {}
};

PseudoHausdorffEnergy::PseudoHausdorffEnergy(const TriangleMesh& target,
                                             const PseudoHausdorffOptions& options)
    : options_(options) {
    detail::require_valid_mesh(target, "PseudoHausdorffEnergy");
    if (target.F.rows() == 0) {
        throw InvalidInput("PseudoHausdorffEnergy: the target mesh has no faces");
    }
    check_options(options, "PseudoHausdorffEnergy");
    impl_ = std::make_unique<Impl>(target, options);
    if (impl_->target.active.empty()) {
        throw InvalidInput("PseudoHausdorffEnergy: the target mesh has zero area");
    }
}

PseudoHausdorffEnergy::~PseudoHausdorffEnergy() = default;
PseudoHausdorffEnergy::PseudoHausdorffEnergy(PseudoHausdorffEnergy&&) noexcept = default;
PseudoHausdorffEnergy& PseudoHausdorffEnergy::operator=(PseudoHausdorffEnergy&&) noexcept = default;

namespace {

PseudoHausdorffEvaluation evaluate_sides(const Side& source, const Side& target,
                                         const PseudoHausdorffOptions& options) {
    const double rounded = std::round(options.alpha);
    const Parameters p{
        options.alpha,
        rounded == options.alpha && rounded >= 1 && rounded <= 64 ? static_cast<int>(rounded) : 0,
        options.epsilon * options.epsilon, options.truncation, options.stored_term_budget};

    const Sums f = sum_over(source, target, p);  // f_i over the target
    const Sums g = sum_over(target, source, p);  // g_j over the source

    // log S = LSE(log a_i − log f_i, log b_j − log g_j); d_H = ε·expm1(log S/(2α) − log ε).
    std::vector<double> terms;
    terms.reserve(source.active.size() + target.active.size());
    for (const std::uint32_t i : source.active) {
        terms.push_back(source.log_weight[i] - f.log_sum[i]);
    }
    for (const std::uint32_t j : target.active) {
        terms.push_back(target.log_weight[j] - g.log_sum[j]);
    }
    const double log_S = log_sum_exp(terms);

    PseudoHausdorffEvaluation result;
    result.value = options.epsilon * std::expm1(log_S / (2 * p.alpha) - std::log(options.epsilon));
    result.pairs = f.pairs + g.pairs;

    // c_ij = S^{1/(2α)−1} a_i b_j d^{−α−1}(f_i^{−2} + g_j^{−2}), as f- and g-parts:
    // f-part = exp(base + log a_i − log f_i)·share_ij/d_ij, and symmetrically for g.
    const double base = (1 / (2 * p.alpha) - 1) * log_S;
    const Eigen::Index n = source.points.rows();
    Eigen::MatrixX4d accumulated = Eigen::MatrixX4d::Zero(n, 4);  // Σc, Σc·y
#pragma omp parallel if (n > kParallelThreshold)
    {
        std::vector<std::pair<std::uint32_t, double>> found;
#pragma omp for schedule(dynamic, 128)
        for (Eigen::Index i = 0; i < n; ++i) {
            if (source.log_weight[i] == kMinusInfinity) {
                continue;
            }
            const double coefficient = std::exp(base + source.log_weight[i] - f.log_sum[i]);
            Eigen::RowVector4d row = Eigen::RowVector4d::Zero();
            for_each_term(source, target, f, p, i, found,
                          [&](std::uint32_t j, double d, double share) {
                              const double c = coefficient * share / d;
                              row[0] += c;
                              row.tail<3>() += c * target.points.row(j);
                          });
            accumulated.row(i) += row;
        }
    }
    std::vector<Eigen::MatrixX4d> scattered(static_cast<std::size_t>(thread_count()));
#pragma omp parallel if (n > kParallelThreshold)
    {
        auto& local = scattered[static_cast<std::size_t>(thread_id())];
        local = Eigen::MatrixX4d::Zero(n, 4);
        std::vector<std::pair<std::uint32_t, double>> found;
#pragma omp for schedule(dynamic, 128)
        for (Eigen::Index j = 0; j < target.points.rows(); ++j) {
            if (target.log_weight[j] == kMinusInfinity) {
                continue;
            }
            const double coefficient = std::exp(base + target.log_weight[j] - g.log_sum[j]);
            const Eigen::RowVector3d y = target.points.row(j);
            for_each_term(target, source, g, p, j, found,
                          [&](std::uint32_t i, double d, double share) {
                              const double c = coefficient * share / d;
                              local(i, 0) += c;
                              local.row(i).tail<3>() += c * y;
                          });
        }
    }
    for (const auto& local : scattered) {
        if (local.rows() == n) {  // threads that never ran leave theirs empty
            accumulated += local;
        }
    }
    result.coupling = accumulated.col(0);
    result.coupled_target = accumulated.rightCols<3>();
    result.differential = (source.points.array().colwise() * result.coupling.array()).matrix() -
                          result.coupled_target;
    return result;
}

}  // namespace

PseudoHausdorffEvaluation pseudo_hausdorff(const Eigen::MatrixX3d& X, const Eigen::VectorXd& mass_x,
                                           const Eigen::MatrixX3d& Y, const Eigen::VectorXd& mass_y,
                                           const PseudoHausdorffOptions& options) {
    check_options(options, "pseudo_hausdorff");
    if (mass_x.size() != X.rows() || mass_y.size() != Y.rows()) {
        throw InvalidInput("pseudo_hausdorff: one mass per point is needed");
    }
    if (!detail::all_finite(X) || !detail::all_finite(Y) ||
        !std::all_of(mass_x.data(), mass_x.data() + mass_x.size(),
                     [](double m) { return m >= 0 && std::isfinite(m); }) ||
        !std::all_of(mass_y.data(), mass_y.data() + mass_y.size(),
                     [](double m) { return m >= 0 && std::isfinite(m); })) {
        throw InvalidInput(
            "pseudo_hausdorff: points and masses must be finite, masses non-negative");
    }
    const Side source(X, mass_x, options.weights, options.truncation > 0);
    const Side target(Y, mass_y, options.weights, options.truncation > 0);
    if (source.active.empty() || target.active.empty()) {
        throw InvalidInput("pseudo_hausdorff: each point set needs a point of positive mass");
    }
    return evaluate_sides(source, target, options);
}

PseudoHausdorffEvaluation PseudoHausdorffEnergy::evaluate(const TriangleMesh& mesh) const {
    detail::require_valid_mesh(mesh, "PseudoHausdorffEnergy::evaluate");
    if (mesh.F.rows() == 0) {
        throw InvalidInput("PseudoHausdorffEnergy::evaluate: mesh has no faces");
    }
    const Side source(mesh.V, lumped_masses(mesh, MassType::Barycentric), options_.weights,
                      options_.truncation > 0);
    if (source.active.empty()) {
        throw InvalidInput("PseudoHausdorffEnergy::evaluate: mesh has zero area");
    }
    return evaluate_sides(source, impl_->target, options_);
}

namespace {

// The evaluation at `mesh`, from the cache when the positions and faces are unchanged.
std::shared_ptr<const PseudoHausdorffEvaluation> cached_evaluation(
    const PseudoHausdorffEnergy& energy, std::mutex& mutex, Eigen::MatrixX3d& cached_V,
    Eigen::MatrixX3i& cached_F, std::shared_ptr<const PseudoHausdorffEvaluation>& cached,
    const TriangleMesh& mesh) {
    {
        const std::lock_guard<std::mutex> lock(mutex);
        if (cached && cached_V.rows() == mesh.V.rows() && cached_F.rows() == mesh.F.rows() &&
            cached_V == mesh.V && cached_F == mesh.F) {
            return cached;
        }
    }
    auto fresh = std::make_shared<const PseudoHausdorffEvaluation>(energy.evaluate(mesh));
    const std::lock_guard<std::mutex> lock(mutex);
    cached_V = mesh.V;
    cached_F = mesh.F;
    cached = fresh;
    return fresh;
}

}  // namespace

double PseudoHausdorffEnergy::value(const TriangleMesh& mesh) const {
    return cached_evaluation(*this, impl_->cache_mutex, impl_->cached_V, impl_->cached_F,
                             impl_->cached, mesh)
        ->value;
}

VertexField PseudoHausdorffEnergy::differential(const TriangleMesh& mesh) const {
    return cached_evaluation(*this, impl_->cache_mutex, impl_->cached_V, impl_->cached_F,
                             impl_->cached, mesh)
        ->differential;
}

std::optional<Linearization> PseudoHausdorffEnergy::linearize(const TriangleMesh& mesh) const {
    const auto evaluation = cached_evaluation(*this, impl_->cache_mutex, impl_->cached_V,
                                              impl_->cached_F, impl_->cached, mesh);
    Linearization linearization;
    linearization.A.resize(mesh.V.rows(), mesh.V.rows());
    linearization.A.reserve(Eigen::VectorXi::Ones(mesh.V.rows()));
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        linearization.A.insert(i, i) = evaluation->coupling[i];
    }
    linearization.A.makeCompressed();
    linearization.B = -evaluation->coupled_target;
    return linearization;
}

}  // namespace genflow
