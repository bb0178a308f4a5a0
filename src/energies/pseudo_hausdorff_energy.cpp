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
#include "spatial/point_grid.h"

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
// ("active") in a grid whose cell order keeps each query's terms contiguous in memory.
using RowMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Side {
    Eigen::MatrixX3d points;
    Eigen::VectorXd log_weight;         // −inf for zero-mass vertices
    std::vector<std::uint32_t> active;  // vertices with positive weight
    double total_weight = 0;
    std::unique_ptr<detail::PointGrid> grid;  // over `active` (grid ids index `active`)
    RowMatrixXd descriptors;                  // per point (PointDescriptors), or no columns
    RowMatrixXd slot_descriptors;             // the same rows in the grid's slot order

    Side(const Eigen::MatrixX3d& positions, const Eigen::VectorXd& masses,
         const PseudoHausdorffOptions& options, const Eigen::MatrixXd& point_descriptors)
        : points(positions), descriptors(point_descriptors) {
        const double mass = masses.sum();
        const double normalizer =
            options.weights == HausdorffWeights::Paper ? static_cast<double>(masses.size()) : mass;
        log_weight.resize(masses.size());
        for (Eigen::Index i = 0; i < masses.size(); ++i) {
            if (masses[i] > 0) {
                log_weight[i] = std::log(masses[i] / normalizer);
                total_weight += masses[i] / normalizer;
                active.push_back(static_cast<std::uint32_t>(i));
            } else {
                log_weight[i] = kMinusInfinity;
            }
        }
        const auto n = static_cast<Eigen::Index>(active.size());
        if (n == 0) {
            return;
        }
        Eigen::MatrixX3d active_points(n, 3);
        Eigen::VectorXd weights(n);
        Eigen::VectorXd kappa2 = Eigen::VectorXd::Ones(n);
        for (Eigen::Index k = 0; k < n; ++k) {
            const std::uint32_t i = active[static_cast<std::size_t>(k)];
            active_points.row(k) = points.row(i);
            weights[k] = std::exp(log_weight[i]);
            if (options.truncation > 0) {  // κ_m² of visit_terms
                kappa2[k] = std::exp(
                    (std::log(total_weight) - log_weight[i] - std::log(options.truncation)) /
                    options.alpha);
            }
        }
        // The radius of a query whose nearest point has the mean weight and lies one mean
        // spacing s away (s² ≈ area per point): κ² (s² + ε²) with κ² = (n/τ)^{1/α}. Cells of a
        // third of it keep the first block (3 cells wide, for the radius) small, and the ball
        // of cells of the second close to the ball of points.
        double cell = 1;
        if (options.truncation > 0) {
            const double spacing2 = mass / static_cast<double>(n);
            const double eps2 = options.epsilon * options.epsilon;
            cell = std::sqrt(std::exp(std::log(static_cast<double>(n) / options.truncation) /
                                      options.alpha) *
                             (spacing2 + eps2)) /
                   3;
        }
        grid = std::make_unique<detail::PointGrid>(active_points, weights, kappa2, cell);
        if (descriptors.cols() > 0) {
            slot_descriptors.resize(n, descriptors.cols());
            for (Eigen::Index slot = 0; slot < n; ++slot) {
                slot_descriptors.row(slot) =
                    descriptors.row(active[grid->id(static_cast<std::uint32_t>(slot))]);
            }
        }
    }

    [[nodiscard]] bool has_descriptors() const { return descriptors.cols() > 0; }
};

struct Parameters {
    double alpha;
    int integer_alpha;  // α when it is an integer in [1, 64], else 0
    double eps2;
    double truncation;
    std::size_t stored_term_budget;
};

using Neighbours = detail::NeighbourList;

// A tighter radius than D's for the query at x (see gather_within_radius), from where the weight
// actually lies: D's bound puts all of W at the radius. With shells [ρ_k, ρ_{k+1}), ρ_k = k·h,
// around x, φ(r) = (r² + ε²)^{−α} decreasing, and M_k the weight at distances in [ρ_K, ρ_{k+1}),
// Abel summation bounds the terms beyond ρ_K by
//     Σ_{k≥K} (φ(ρ_k) − φ(ρ_{k+1})) M_k  ≤  Σ_{K≤k<E} (φ_k − φ_{k+1}) min(W, B_k) + φ_E W,
// where B_k, the weight of the cells within ⌈ρ_{k+1}/cell⌉ rings of x's cell, holds every point
// closer than ρ_{k+1}. The smallest K for which this is ≤ W D^{−α} (≤ τ f_u, as above) gives the
// radius ρ_K; E, the first shell with ρ_E² + ε² ≥ D, has φ_E W ≤ W D^{−α} already. The sums
// run in units of W D^{−α}, ψ_k = (D/(ρ_k² + ε²))^α, and stop before they could overflow.
// Returns +inf when no shell can be dropped.
double shell_radius2(const detail::PointGrid& grid, const Eigen::Vector3d& x, double D,
                     const Parameters& p, double total_weight) {
    constexpr int kShellsPerCell = 4;
    constexpr double kNoShell = std::numeric_limits<double>::infinity();
    // Slightly inside the cells, so that rounding cannot put a point closer than ρ_{k+1}
    // outside the block of ⌈ρ_{k+1}/cell⌉ rings.
    const double step = grid.cell_size() * (1 - 1e-9) / kShellsPerCell;
    const double reach2 = D - p.eps2;
    if (!(reach2 > 0)) {
        return kNoShell;
    }
    constexpr int kMaxShells = 4096;  // beyond, far apart: nearly all of W lies beyond any ρ_K
    if (!(std::sqrt(reach2) <= kMaxShells * step)) {
        return kNoShell;
    }
    const int end = static_cast<int>(std::ceil(std::sqrt(reach2) / step));
    const double log_D = std::log(D);
    const auto log_psi = [&](int k) {
        const double rho = static_cast<double>(k) * step;
        return p.alpha * (log_D - std::log(rho * rho + p.eps2));
    };
    double tail = std::exp(std::min(log_psi(end), 0.0));  // φ_E W: at most 1
    double psi_next = tail;
    int first_kept = end;
    for (int k = end - 1; k >= 1; --k) {
        const double log_psi_k = log_psi(k);
        if (log_psi_k > 600) {
            break;
        }
        const double psi = std::exp(log_psi_k);
        const int rings = (k + kShellsPerCell) / kShellsPerCell;  // ⌈(k + 1)/kShellsPerCell⌉
        // (+1e-12: the prefix sums may round a block's weight down.)
        const double fraction =
            std::clamp(grid.block_weight(x, rings) / total_weight + 1e-12, 0.0, 1.0);
        tail += (psi - psi_next) * fraction;
        if (tail > 1) {
            break;
        }
        psi_next = psi;
        first_kept = k;
    }
    const double rho = static_cast<double>(first_kept) * step;
    return first_kept == end ? kNoShell : rho * rho;
}

// The truncation radius (as a squared distance) of the query at x, with the points within it
// in `found`. Adaptive radius (SPEC.md §8): for any point m at d_m = |x − y_m|² + ε²,
// weight_m d_m^{−α} ≤ f_u, so everything beyond d = κ_m² d_m adds at most
// W (κ_m² d_m)^{−α} = τ weight_m d_m^{−α} ≤ τ f_u, with κ_m² = (W/(weight_m τ))^{1/α}. D, the
// smallest κ_m² d_m over a first small block (`smallest_scaled(rings)`: over the block of that
// many rings, 0 for all points; +inf for an empty block), gives a radius; shell_radius2()
// shrinks it.
template <typename SmallestScaled>
double gather_within_radius(const detail::PointGrid& grid, const Eigen::Vector3d& x,
                            const Parameters& p, double total_weight,
                            SmallestScaled&& smallest_scaled, Neighbours& found) {
    double radius2 = std::numeric_limits<double>::infinity();
    for (const int rings : {1, 4, 0}) {
        const double radius_d = smallest_scaled(rings);
        if (radius_d < std::numeric_limits<double>::infinity()) {
            radius2 = std::min((radius_d - p.eps2) * (1 + 1e-12),
                               shell_radius2(grid, x, radius_d, p, total_weight));
            break;  // the last pass, over all points, always finds one
        }
    }
    grid.collect_within(x, grid.rings_to_cover(std::sqrt(radius2)), radius2, found);
    return radius2;
}

// Adds |φ_u − ψ_slot|² (PointDescriptors) to the squared distances in `found`.
void add_descriptor_distances(const Side& from, const Side& to, Eigen::Index u, Neighbours& found) {
    const auto phi = from.descriptors.row(u);
    for (std::size_t k = 0; k < found.count; ++k) {
        found.distances2[k] +=
            (to.slot_descriptors.row(static_cast<Eigen::Index>(found.slots[k])) - phi)
                .squaredNorm();
    }
}

// The smallest κ_m² d_m over the block of `rings` around the query u, with descriptors. D must
// come from the full distances d_m of R^{3+k} (a smaller one would drop more than the bound
// allows), so the block's points are collected (into `found`) and their descriptor distances
// added. The radius then bounds the spatial part |x − y|² ≤ d − ε², which keeps every term
// with d ≤ D; the shell bound stays valid because the descriptors only make each term smaller.
double smallest_scaled_with_descriptors(const Side& from, const Side& to, const Parameters& p,
                                        Eigen::Index u, int rings, Neighbours& found) {
    const detail::PointGrid& grid = *to.grid;
    grid.collect_within(from.points.row(u).transpose(), rings,
                        std::numeric_limits<double>::infinity(), found);
    add_descriptor_distances(from, to, u, found);
    double smallest = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < found.count; ++k) {
        smallest = std::min(smallest, grid.factor(found.slots[k]) * (found.distances2[k] + p.eps2));
    }
    return smallest;
}

// Calls visit(slot, d, t) for every kept term of f_u = Σ_w weight_w d_uw^{−α}, where `slot`
// is w's place in to.grid and the term is scaled by the nearest one's d*^α so that nothing
// overflows: t = weight_w (d*/d_uw)^α. Returns d*, so that log f_u = log Σt − α log d*.
// (With descriptors, d and d* are the distances of R^{3+k}.)
template <typename Visit>
double visit_terms(const Side& from, const Side& to, const Parameters& p, Eigen::Index u,
                   Neighbours& found, Visit&& visit) {
    const Eigen::Vector3d x = from.points.row(u).transpose();
    const detail::PointGrid& grid = *to.grid;
    if (p.truncation <= 0) {
        grid.collect_within(x, 0, std::numeric_limits<double>::infinity(), found);
    } else if (from.has_descriptors()) {
        gather_within_radius(
            grid, x, p, to.total_weight,
            [&](int rings) {
                return smallest_scaled_with_descriptors(from, to, p, u, rings, found);
            },
            found);
    } else {
        gather_within_radius(
            grid, x, p, to.total_weight,
            [&](int rings) { return grid.min_scaled_distance(x, rings, p.eps2); }, found);
    }
    if (from.has_descriptors()) {
        add_descriptor_distances(from, to, u, found);
    }
    double nearest2 = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < found.count; ++k) {
        nearest2 = std::min(nearest2, found.distances2[k]);
    }
    const double d_star = nearest2 + p.eps2;  // κ_m ≥ 1: the point m itself is kept
    for (std::size_t k = 0; k < found.count; ++k) {
        const std::uint32_t slot = found.slots[k];
        const double d = found.distances2[k] + p.eps2;
        visit(slot, d, grid.weight(slot) * ratio_power(d_star / d, p.alpha, p.integer_alpha));
    }
    return d_star;
}

using RowMatrixX4d = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;

// The source side of the sums: f_i over the target, and the moments Σ_j share_ij/d_ij·[1, y_j]
// with share_ij = b_j d_ij^{−α}/f_i, from which the f-part of Σ_j c_ij and Σ_j c_ij y_j follow
// once S is known. Nothing per pair is kept.
struct SourceSums {
    Eigen::VectorXd log_f;  // −inf for inactive points
    RowMatrixX4d moments;
    std::size_t pairs = 0;
};

SourceSums sum_source(const Side& source, const Side& target, const Parameters& p) {
    const Eigen::Index count = source.points.rows();
    SourceSums sums{Eigen::VectorXd::Constant(count, kMinusInfinity), RowMatrixX4d::Zero(count, 4),
                    0};
    const detail::PointGrid& grid = *target.grid;
    // Queries in the cell order of their own grid: neighbouring queries share their terms
    // in cache.
    const std::size_t queries = source.active.size();
    std::size_t pairs = 0;
#pragma omp parallel reduction(+ : pairs) if (count > kParallelThreshold)
    {
        Neighbours found;
#pragma omp for schedule(static, 128)
        for (std::size_t slot = 0; slot < queries; ++slot) {
            const std::uint32_t i =
                source.active[source.grid->id(static_cast<std::uint32_t>(slot))];
            double sum = 0;
            Eigen::RowVector4d moment = Eigen::RowVector4d::Zero();
            const double d_star = visit_terms(
                source, target, p, i, found, [&](std::uint32_t term, double d, double t) {
                    sum += t;
                    const double s = t / d;
                    moment[0] += s;
                    moment.tail<3>() += s * grid.position(term).transpose();
                });
            pairs += found.count;
            sums.log_f[i] = std::log(sum) - p.alpha * std::log(d_star);
            sums.moments.row(i) = moment / sum;
        }
    }
    sums.pairs = pairs;
    return sums;
}

// A kept term of g_j for the gradient pass: the source point i and share_ji/d_ij with
// share_ji = a_i d_ij^{−α}/g_j.
struct TargetTerm {
    std::uint32_t source;
    std::uint32_t target;
    double share_over_d;
};

// Per-thread buffers of the target side, reused from one evaluation to the next.
struct Workspace {
    std::vector<std::vector<TargetTerm>> kept;       // per thread
    std::vector<std::vector<std::uint32_t>> redone;  // per thread: points to query again
};

// Appends the terms of g_j (over the source) to `terms` and returns log g_j.
double append_target_terms(const Side& target, const Side& source, const Parameters& p,
                           Eigen::Index j, Neighbours& found, std::vector<TargetTerm>& terms) {
    const std::size_t first = terms.size();
    const auto index = static_cast<std::uint32_t>(j);
    const detail::PointGrid& grid = *source.grid;
    double sum = 0;
    const double d_star =
        visit_terms(target, source, p, j, found, [&](std::uint32_t slot, double d, double t) {
            sum += t;
            terms.push_back({source.active[grid.id(slot)], index, t / d});
        });
    const double scale = 1 / sum;
    for (std::size_t k = first; k < terms.size(); ++k) {
        terms[k].share_over_d *= scale;
    }
    return std::log(sum) - p.alpha * std::log(d_star);
}

// The target side: g_j over the source, with its terms kept (per thread, up to the budget)
// because they scatter into the source rows only once S is known; the points beyond the
// budget are listed for a second neighbour query.
struct TargetSums {
    Eigen::VectorXd log_g;
    std::size_t pairs = 0;
};

TargetSums sum_target(const Side& target, const Side& source, const Parameters& p,
                      Workspace& work) {
    const Eigen::Index count = target.points.rows();
    TargetSums sums{Eigen::VectorXd::Constant(count, kMinusInfinity), 0};
    const auto threads = static_cast<std::size_t>(thread_count());
    work.kept.resize(threads);
    work.redone.resize(threads);
    for (std::size_t t = 0; t < threads; ++t) {
        work.kept[t].clear();
        work.redone[t].clear();
    }
    std::atomic<std::size_t> kept_terms{0};
    const std::size_t queries = target.active.size();  // in cell order, as in sum_source
    std::size_t pairs = 0;
#pragma omp parallel reduction(+ : pairs) if (count > kParallelThreshold)
    {
        Neighbours found;
        auto& kept = work.kept[static_cast<std::size_t>(thread_id())];
        auto& redone = work.redone[static_cast<std::size_t>(thread_id())];
#pragma omp for schedule(static, 128)
        for (std::size_t slot = 0; slot < queries; ++slot) {
            const std::uint32_t j =
                target.active[target.grid->id(static_cast<std::uint32_t>(slot))];
            const std::size_t first = kept.size();
            sums.log_g[j] = append_target_terms(target, source, p, j, found, kept);
            const std::size_t terms = kept.size() - first;
            pairs += terms;
            if (kept_terms.fetch_add(terms) + terms > p.stored_term_budget) {
                kept.resize(first);
                redone.push_back(static_cast<std::uint32_t>(j));
            }
        }
    }
    sums.pairs = pairs;
    return sums;
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

// Checks that `descriptors` fit point sets of `moving` and `fixed` rows (when it has any
// columns): as many columns on both sides, a row per point, finite values.
void check_descriptors(const PointDescriptors& descriptors, Eigen::Index moving, Eigen::Index fixed,
                       const char* caller) {
    if (descriptors.moving.cols() == 0 && descriptors.fixed.cols() == 0) {
        return;
    }
    if (descriptors.moving.cols() != descriptors.fixed.cols()) {
        throw InvalidInput(std::string(caller) + ": the descriptors have " +
                           std::to_string(descriptors.moving.cols()) + " and " +
                           std::to_string(descriptors.fixed.cols()) +
                           " columns; both sides need the same");
    }
    if ((moving >= 0 && descriptors.moving.rows() != moving) || descriptors.fixed.rows() != fixed) {
        throw InvalidInput(std::string(caller) + ": the descriptors need a row per point (" +
                           std::to_string(descriptors.moving.rows()) + " and " +
                           std::to_string(descriptors.fixed.rows()) + " rows for " +
                           std::to_string(moving) + " and " + std::to_string(fixed) + " points)");
    }
    if (!descriptors.moving.allFinite() || !descriptors.fixed.allFinite()) {
        throw InvalidInput(std::string(caller) + ": the descriptors must be finite");
    }
}

}  // namespace

struct PseudoHausdorffEnergy::Impl {
    Eigen::MatrixXd moving_descriptors;  // no columns without descriptors
    Side target;
    std::mutex cache_mutex;
    Eigen::MatrixX3d cached_V;
    Eigen::MatrixX3i cached_F;
    std::shared_ptr<const PseudoHausdorffEvaluation> cached;
    std::mutex workspace_mutex;
    Workspace workspace;

    Impl(const TriangleMesh& mesh, const PseudoHausdorffOptions& options,
         PointDescriptors descriptors)
        : moving_descriptors(std::move(descriptors.moving)),
          target(mesh.V, lumped_masses(mesh, MassType::Barycentric), options, descriptors.fixed) {}
};

PseudoHausdorffEnergy::PseudoHausdorffEnergy(const TriangleMesh& target,
                                             const PseudoHausdorffOptions& options)
    : PseudoHausdorffEnergy(target, options, PointDescriptors{}) {}

PseudoHausdorffEnergy::PseudoHausdorffEnergy(const TriangleMesh& target,
                                             const PseudoHausdorffOptions& options,
                                             PointDescriptors descriptors)
    : options_(options) {
    detail::require_valid_mesh(target, "PseudoHausdorffEnergy");
    if (target.F.rows() == 0) {
        throw InvalidInput("PseudoHausdorffEnergy: the target mesh has no faces");
    }
    check_options(options, "PseudoHausdorffEnergy");
    check_descriptors(descriptors, -1, target.V.rows(), "PseudoHausdorffEnergy");
    impl_ = std::make_unique<Impl>(target, options, std::move(descriptors));
    if (impl_->target.active.empty()) {
        throw InvalidInput("PseudoHausdorffEnergy: the target mesh has zero area");
    }
}

PseudoHausdorffEnergy::~PseudoHausdorffEnergy() = default;
PseudoHausdorffEnergy::PseudoHausdorffEnergy(PseudoHausdorffEnergy&&) noexcept = default;
PseudoHausdorffEnergy& PseudoHausdorffEnergy::operator=(PseudoHausdorffEnergy&&) noexcept = default;

namespace {

PseudoHausdorffEvaluation evaluate_sides(const Side& source, const Side& target,
                                         const PseudoHausdorffOptions& options, Workspace& work) {
    const double rounded = std::round(options.alpha);
    const Parameters p{
        options.alpha,
        rounded == options.alpha && rounded >= 1 && rounded <= 64 ? static_cast<int>(rounded) : 0,
        options.epsilon * options.epsilon, options.truncation, options.stored_term_budget};

    const TargetSums g = sum_target(target, source, p, work);  // g_j over the source
    const SourceSums f = sum_source(source, target, p);        // f_i over the target

    // log S = LSE(log a_i − log f_i, log b_j − log g_j); d_H = ε·expm1(log S/(2α) − log ε).
    std::vector<double> terms;
    terms.reserve(source.active.size() + target.active.size());
    for (const std::uint32_t i : source.active) {
        terms.push_back(source.log_weight[i] - f.log_f[i]);
    }
    for (const std::uint32_t j : target.active) {
        terms.push_back(target.log_weight[j] - g.log_g[j]);
    }
    const double log_S = log_sum_exp(terms);

    PseudoHausdorffEvaluation result;
    result.value = options.epsilon * std::expm1(log_S / (2 * p.alpha) - std::log(options.epsilon));
    result.pairs = f.pairs + g.pairs;

    // c_ij = S^{1/(2α)−1} a_i b_j d^{−α−1}(f_i^{−2} + g_j^{−2}), as f- and g-parts:
    // f-part = exp(base + log a_i − log f_i)·share_ij/d_ij, and symmetrically for g. The
    // coefficients are formed in the log domain: S^{1/(2α)−1} alone may overflow.
    const double base = (1 / (2 * p.alpha) - 1) * log_S;
    const Eigen::Index n = source.points.rows();
    Eigen::VectorXd target_coefficient = Eigen::VectorXd::Zero(target.points.rows());
    for (const std::uint32_t j : target.active) {
        target_coefficient[j] = std::exp(base + target.log_weight[j] - g.log_g[j]);
    }
    RowMatrixX4d accumulated = RowMatrixX4d::Zero(n, 4);  // Σc, Σc·y
    for (const std::uint32_t i : source.active) {
        accumulated.row(i) = std::exp(base + source.log_weight[i] - f.log_f[i]) * f.moments.row(i);
    }
    // The g-part scatters into source rows: each thread into its own copy.
    std::vector<RowMatrixX4d> scattered(static_cast<std::size_t>(thread_count()));
#pragma omp parallel if (n > kParallelThreshold)
    {
        const auto thread = static_cast<std::size_t>(thread_id());
        auto& local = scattered[thread];
        local = RowMatrixX4d::Zero(n, 4);
        const auto scatter = [&](const std::vector<TargetTerm>& kept_terms) {
            for (const TargetTerm& term : kept_terms) {
                const double c = target_coefficient[term.target] * term.share_over_d;
                local(term.source, 0) += c;
                local.row(term.source).tail<3>() += c * target.points.row(term.target);
            }
        };
        // Each thread scatters the terms it kept, then shares the points to query again.
        scatter(work.kept[thread]);
        Neighbours found;
        std::vector<TargetTerm> again;
        for (const auto& redone : work.redone) {
#pragma omp for schedule(static, 128)
            for (std::size_t k = 0; k < redone.size(); ++k) {
                again.clear();
                append_target_terms(target, source, p, redone[k], found, again);
                scatter(again);
            }
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
                                           const PseudoHausdorffOptions& options,
                                           const PointDescriptors& descriptors) {
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
    check_descriptors(descriptors, X.rows(), Y.rows(), "pseudo_hausdorff");
    const Side source(X, mass_x, options, descriptors.moving);
    const Side target(Y, mass_y, options, descriptors.fixed);
    if (source.active.empty() || target.active.empty()) {
        throw InvalidInput("pseudo_hausdorff: each point set needs a point of positive mass");
    }
    Workspace work;
    return evaluate_sides(source, target, options, work);
}

PseudoHausdorffEvaluation PseudoHausdorffEnergy::evaluate(const TriangleMesh& mesh) const {
    detail::require_valid_mesh(mesh, "PseudoHausdorffEnergy::evaluate");
    if (mesh.F.rows() == 0) {
        throw InvalidInput("PseudoHausdorffEnergy::evaluate: mesh has no faces");
    }
    const Eigen::MatrixXd& descriptors = impl_->moving_descriptors;
    if (descriptors.cols() > 0 && descriptors.rows() != mesh.V.rows()) {
        throw InvalidInput("PseudoHausdorffEnergy::evaluate: the mesh has " +
                           std::to_string(mesh.V.rows()) + " vertices but " +
                           std::to_string(descriptors.rows()) + " descriptor rows");
    }
    const Side source(mesh.V, lumped_masses(mesh, MassType::Barycentric), options_, descriptors);

    if (source.active.empty()) {
        throw InvalidInput("PseudoHausdorffEnergy::evaluate: mesh has zero area");
    }
    // The buffers of the last evaluation are reused (sparing ~20 MB of page faults per call on
    // a 28K × 21K pair) unless another thread is evaluating.
    std::unique_lock<std::mutex> lock(impl_->workspace_mutex, std::try_to_lock);
    if (lock.owns_lock()) {
        return evaluate_sides(source, impl_->target, options_, impl_->workspace);
    }
    Workspace work;
    return evaluate_sides(source, impl_->target, options_, work);
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
