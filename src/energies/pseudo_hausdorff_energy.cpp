// SPDX-License-Identifier: MIT
#include "genflow/energies/pseudo_hausdorff_energy.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/operators/mass_matrix.h"
#include "operators/triangle.h"
#include "spatial/point_grid.h"

namespace genflow {

namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();
// Below this many points a thread team costs more than it saves: for the neighbour sums, and
// for the loops of a few operations per point (whose team is worth it on large meshes only,
// and whose barriers cost most when the cores are shared). Below them a loop runs without a
// region: one of a single thread still makes libgomp a team and a futex call (two when nested
// in the side-by-side flows of a match), some 6 regions an evaluation.
constexpr Eigen::Index kParallelThreshold = 2000;
constexpr Eigen::Index kParallelLoopThreshold = 20000;
// The shells of shell_radius2(): this many per grid cell, and at most this many per query.
constexpr int kShellsPerCell = 4;
constexpr int kMaxShells = 4096;

// Calls body(k) for k in [0, count): in a region, statically scheduled, when `parallel`, else
// on the calling thread with no region (see kParallelThreshold).
template <typename Body>
void for_each_index(std::ptrdiff_t count, bool parallel, Body&& body) {
    if (!parallel) {
        for (std::ptrdiff_t k = 0; k < count; ++k) {
            body(k);
        }
        return;
    }
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
        body(k);
    }
}

// log Σ exp(v) over the finite entries; −inf if there is none. The threads compute the terms,
// and one sums them in order: the same bits for any thread count (per-thread partial sums
// depended on how many threads shared the loop).
double log_sum_exp(const std::vector<double>& values) {
    double largest = kMinusInfinity;
    for (const double v : values) {
        largest = std::max(largest, v);
    }
    if (largest == kMinusInfinity) {
        return kMinusInfinity;
    }
    const auto count = static_cast<std::ptrdiff_t>(values.size());
    std::vector<double> terms(values.size());
    const auto exponentiate = [&](std::ptrdiff_t k) {
        terms[static_cast<std::size_t>(k)] =
            std::exp(values[static_cast<std::size_t>(k)] - largest);
    };
    for_each_index(count, count > kParallelLoopThreshold, exponentiate);
    double sum = 0;
    for (const double term : terms) {
        sum += term;
    }
    return largest + std::log(sum);
}

// r^8, the default α spelled out: ratio_power()'s loop costs, in its shifts and branches, as
// much as the products in the innermost sums. It squares as the loop does, so the result is the
// same to the bit.
double eighth_power(double r) {
    const double r2 = r * r;
    const double r4 = r2 * r2;
    return r4 * r4;
}

// r^α for 0 < r ≤ 1, by repeated squaring when α is a small integer (`integer_alpha`, the usual
// 8 or 16), else by std::pow.
double ratio_power(double r, double alpha, int integer_alpha) {
    if (integer_alpha == 8) {
        return eighth_power(r);
    }
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
    detail::PointGrid grid;  // over `active` (grid ids index `active`)
    // The row in `points` of the point at each grid slot (active[grid.id(slot)]), found once a
    // gridding: the sums read it for every term.
    std::vector<std::uint32_t> point_at_slot;
    RowMatrixXd descriptors;       // per point (PointDescriptors), or no columns
    RowMatrixXd slot_descriptors;  // the same rows in the grid's slot order
    // |φ − ψ|² of this side's points (rows) against the other side's (columns, see
    // table_columns()), when the energy tabulated them (DescriptorTable); else null.
    const RowMatrixXd* descriptor_table = nullptr;
    // Whether the other side's table has a column per grid slot of this side (the target's
    // slots never change) or per point (the moving side is gridded anew at every evaluation).
    bool table_columns_by_slot = false;
    // The shells of shell_radius2() about a query: ρ_k = k·shell_step, and 1/(ρ_k² + ε²).
    double shell_step = 1;
    std::vector<double> inverse_shell_d;

    Side() = default;
    Side(const Eigen::MatrixX3d& positions, const Eigen::VectorXd& masses,
         const PseudoHausdorffOptions& options, const Eigen::MatrixXd& point_descriptors) {
        assign(positions, masses, options, point_descriptors);
    }

    // Refills this side in place: the moving side is rebuilt at every evaluation, and reusing
    // its buffers spares the page faults of fresh ones.
    void assign(const Eigen::MatrixX3d& positions, const Eigen::VectorXd& masses,
                const PseudoHausdorffOptions& options, const Eigen::MatrixXd& point_descriptors) {
        points = positions;
        descriptors = point_descriptors;
        const double mass = masses.sum();
        const double normalizer =
            options.weights == HausdorffWeights::Paper ? static_cast<double>(masses.size()) : mass;
        active.clear();
        total_weight = 0;
        for (Eigen::Index i = 0; i < masses.size(); ++i) {
            if (masses[i] > 0) {
                total_weight += masses[i] / normalizer;
                active.push_back(static_cast<std::uint32_t>(i));
            }
        }
        log_weight.resize(masses.size());
        const auto n = static_cast<Eigen::Index>(active.size());
        grid_points_.resize(n, 3);
        grid_weights_.resize(n);
        grid_factors_.resize(n);
        // κ_m² of gather_within_radius: (W/(weight_m τ))^{1/α}.
        const double log_kappa_base =
            options.truncation > 0 ? std::log(total_weight) - std::log(options.truncation) : 0;
        const auto weigh_point = [&](Eigen::Index i) {
            log_weight[i] = masses[i] > 0 ? std::log(masses[i] / normalizer) : kMinusInfinity;
        };
        const auto grid_point = [&](Eigen::Index k) {
            const std::uint32_t i = active[static_cast<std::size_t>(k)];
            grid_points_.row(k) = points.row(i);
            grid_weights_[k] = masses[i] / normalizer;
            grid_factors_[k] = options.truncation > 0
                                   ? std::exp((log_kappa_base - log_weight[i]) / options.alpha)
                                   : 1.0;
        };
        const bool parallel = masses.size() > kParallelLoopThreshold;
        for_each_index(masses.size(), parallel, weigh_point);
        for_each_index(n, parallel, grid_point);
        if (n == 0) {
            point_at_slot.clear();
            return;
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
        grid.rebuild(grid_points_, grid_weights_, grid_factors_, cell);
        if (options.truncation > 0) {
            // Slightly inside the cells, so that rounding cannot put a point closer than
            // ρ_{k+1} outside the block of ⌈ρ_{k+1}/cell⌉ rings.
            shell_step = grid.cell_size() * (1 - 1e-9) / kShellsPerCell;
            const double eps2 = options.epsilon * options.epsilon;
            inverse_shell_d.resize(kMaxShells + 1);
            for (int k = 0; k <= kMaxShells; ++k) {
                const double rho = static_cast<double>(k) * shell_step;
                inverse_shell_d[static_cast<std::size_t>(k)] = 1 / (rho * rho + eps2);
            }
        }
        point_at_slot.resize(active.size());
        for (std::size_t slot = 0; slot < active.size(); ++slot) {
            point_at_slot[slot] = active[grid.id(static_cast<std::uint32_t>(slot))];
        }
        if (descriptors.cols() > 0) {
            slot_descriptors.resize(n, descriptors.cols());
            for (Eigen::Index slot = 0; slot < n; ++slot) {
                slot_descriptors.row(slot) =
                    descriptors.row(point_at_slot[static_cast<std::size_t>(slot)]);
            }
        }
    }

    [[nodiscard]] bool has_descriptors() const { return descriptors.cols() > 0; }

    // The columns of the other side's descriptor table by this side's grid slots: null when
    // they are the slots themselves.
    [[nodiscard]] const std::uint32_t* table_columns() const {
        return table_columns_by_slot ? nullptr : point_at_slot.data();
    }

private:
    // The active points, their weights and κ² in `active` order, for the grid.
    Eigen::MatrixX3d grid_points_;
    Eigen::VectorXd grid_weights_;
    Eigen::VectorXd grid_factors_;
};

struct Parameters {
    double alpha;
    int integer_alpha;  // α when it is an integer in [1, 64], else 0
    double eps2;
    double truncation;
    double largest_shell_ratio;  // e^{600/α}: ψ_k = ratio^α stays below e^600
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
double shell_radius2(const Side& to, const Eigen::Vector3d& x, double D, const Parameters& p) {
    constexpr double kNoShell = std::numeric_limits<double>::infinity();
    const double step = to.shell_step;
    const double reach2 = D - p.eps2;
    if (!(reach2 > 0)) {
        return kNoShell;
    }
    if (!(std::sqrt(reach2) <= kMaxShells * step)) {
        return kNoShell;  // far apart: nearly all of W lies beyond any ρ_K
    }
    const int end = static_cast<int>(std::ceil(std::sqrt(reach2) / step));
    // ψ_k = (D/(ρ_k² + ε²))^α from the side's table of 1/(ρ_k² + ε²).
    const auto psi = [&](int k) {
        return ratio_power(D * to.inverse_shell_d[static_cast<std::size_t>(k)], p.alpha,
                           p.integer_alpha);
    };
    double tail = std::min(psi(end), 1.0);  // φ_E W: at most 1
    double psi_next = tail;
    int first_kept = end;
    int rings = 0;
    double fraction = 0;
    for (int k = end - 1; k >= 1; --k) {
        if (D * to.inverse_shell_d[static_cast<std::size_t>(k)] > p.largest_shell_ratio) {
            break;  // ψ_k would overflow
        }
        const double psi_k = psi(k);
        const int rings_k = (k + kShellsPerCell) / kShellsPerCell;  // ⌈(k + 1)/kShellsPerCell⌉
        if (rings_k != rings) {
            rings = rings_k;
            // (+1e-12: the prefix sums may round a block's weight down.)
            fraction =
                std::clamp(to.grid.block_weight(x, rings) / to.total_weight + 1e-12, 0.0, 1.0);
        }
        tail += (psi_k - psi_next) * fraction;
        if (tail > 1) {
            break;
        }
        psi_next = psi_k;
        first_kept = k;
    }
    const double rho = static_cast<double>(first_kept) * step;
    return first_kept == end ? kNoShell : rho * rho;
}

// The truncation radius (as a squared distance) of the query at x, with the points within it
// in `found`. Adaptive radius (docs/formulas.md §8): for any point m at d_m = |x − y_m|² + ε²,
// weight_m d_m^{−α} ≤ f_u, so everything beyond d = κ_m² d_m adds at most
// W (κ_m² d_m)^{−α} = τ weight_m d_m^{−α} ≤ τ f_u, with κ_m² = (W/(weight_m τ))^{1/α}. D, the
// smallest κ_m² d_m over a first small block (`smallest_scaled(rings)`: over the block of that
// many rings, 0 for all points; +inf for an empty block), gives a radius; shell_radius2()
// shrinks it.
template <typename SmallestScaled>
double gather_within_radius(const Side& to, const Eigen::Vector3d& x, const Parameters& p,
                            SmallestScaled&& smallest_scaled, Neighbours& found) {
    const detail::PointGrid& grid = to.grid;
    double radius2 = std::numeric_limits<double>::infinity();
    for (const int rings : {1, 4, 0}) {
        const double radius_d = smallest_scaled(rings);
        if (radius_d < std::numeric_limits<double>::infinity()) {
            radius2 =
                std::min((radius_d - p.eps2) * (1 + 1e-12), shell_radius2(to, x, radius_d, p));
            break;  // the last pass, over all points, always finds one
        }
    }
    grid.collect_within(x, grid.rings_to_cover(std::sqrt(radius2)), radius2, found);
    return radius2;
}

// Returns use(distance), where distance(slot) is |φ_u − ψ_slot|² (PointDescriptors) of `from`'s
// point u and `to`'s point at `slot`: read from the table when there is one (by the column of the
// slot's point, or by the slot itself), else computed, the same value either way. One form per
// call, so that the loops in `use` have no branch per term.
template <typename Use>
decltype(auto) with_descriptor_distance(const Side& from, const Side& to, Eigen::Index u,
                                        Use&& use) {
    if (from.descriptor_table != nullptr) {
        const double* row = from.descriptor_table->row(u).data();
        if (const std::uint32_t* columns = to.table_columns()) {
            return use([row, columns](std::uint32_t slot) { return row[columns[slot]]; });
        }
        return use([row](std::uint32_t slot) { return row[slot]; });
    }
    const auto phi = from.descriptors.row(u);
    return use([&to, phi](std::uint32_t slot) {
        return (to.slot_descriptors.row(static_cast<Eigen::Index>(slot)) - phi).squaredNorm();
    });
}

// Adds |φ_u − ψ_slot|² (PointDescriptors) to the squared distances in `found`.
void add_descriptor_distances(const Side& from, const Side& to, Eigen::Index u, Neighbours& found) {
    with_descriptor_distance(from, to, u, [&found](auto distance) {
        const std::uint32_t* slots = found.slots.data();
        double* distances2 = found.distances2.data();
        for (std::size_t k = 0; k < found.count; ++k) {
            distances2[k] += distance(slots[k]);
        }
    });
}

// The smallest κ_m² d_m over the block of `rings` around the query u, with descriptors. D must
// come from the full distances d_m of R^{3+k} (a smaller one would drop more than the bound
// allows), so each of the block's points has its descriptor distance added, in one pass that
// keeps nothing. The radius then bounds the spatial part |x − y|² ≤ d − ε², which keeps every
// term with d ≤ D; the shell bound stays valid because the descriptors only make each term
// smaller.
double smallest_scaled_with_descriptors(const Side& from, const Side& to, const Parameters& p,
                                        Eigen::Index u, int rings) {
    const Eigen::Vector3d x = from.points.row(u).transpose();
    return with_descriptor_distance(from, to, u, [&](auto distance) {
        return to.grid.min_scaled_distance(x, rings, p.eps2, distance);
    });
}

// The kept terms of f_u = Σ_w weight_w d_uw^{−α}, each scaled by the nearest one's d*^α so that
// nothing overflows: t_w = weight_w (d*/d_uw)^α. Leaves in `found.slots` the places of the kept
// w in to.grid and in `term_over_d` (grown as needed) t_w/d_uw, which the gradient needs.
// (With descriptors, d and d* are the distances of R^{3+k}.)
struct KeptTerms {
    double sum;    // Σ_w t_w
    double log_f;  // log f_u = log Σt − α log d*
};

KeptTerms weigh_terms(const Side& from, const Side& to, const Parameters& p, Eigen::Index u,
                      Neighbours& found, std::vector<double>& term_over_d) {
    const Eigen::Vector3d x = from.points.row(u).transpose();
    const detail::PointGrid& grid = to.grid;
    if (p.truncation <= 0) {
        grid.collect_within(x, 0, std::numeric_limits<double>::infinity(), found);
    } else if (from.has_descriptors()) {
        gather_within_radius(
            to, x, p,
            [&](int rings) { return smallest_scaled_with_descriptors(from, to, p, u, rings); },
            found);
    } else {
        gather_within_radius(
            to, x, p, [&](int rings) { return grid.min_scaled_distance(x, rings, p.eps2); }, found);
    }
    if (from.has_descriptors()) {
        add_descriptor_distances(from, to, u, found);
    }
    const std::size_t count = found.count;
    const double* distances2 = found.distances2.data();
    const std::uint32_t* slots = found.slots.data();
    // Two minima break the dependency chain of one (the minimum is exact in any order).
    double nearest_even = std::numeric_limits<double>::infinity();
    double nearest_odd = nearest_even;
    std::size_t k = 0;
    for (; k + 1 < count; k += 2) {
        nearest_even = std::min(nearest_even, distances2[k]);
        nearest_odd = std::min(nearest_odd, distances2[k + 1]);
    }
    if (k < count) {
        nearest_even = std::min(nearest_even, distances2[k]);
    }
    const double nearest2 = std::min(nearest_even, nearest_odd);
    const double eps2 = p.eps2;             // a local: the stores below could alias `p`
    const double d_star = nearest2 + eps2;  // κ_m ≥ 1: the point m itself is kept
    if (term_over_d.size() < count) {
        term_over_d.resize(std::max(count, 2 * term_over_d.size()));
    }
    double* out = term_over_d.data();
    // The divisions first, in a loop of their own that the compiler vectorizes (they cost
    // most, and the sum below keeps them from overlapping); correctly rounded, they are the
    // same to the bit.
    for (std::size_t j = 0; j < count; ++j) {
        out[j] = 1 / (distances2[j] + eps2);
    }
    // The power inlined for the default α = 8, the loop's other costs being a few operations.
    const auto weigh = [&](auto power) {
        double sum = 0;
        for (std::size_t j = 0; j < count; ++j) {
            const double inverse_d = out[j];
            const double t = grid.weight(slots[j]) * power(d_star * inverse_d);
            sum += t;
            out[j] = t * inverse_d;
        }
        return sum;
    };
    const double sum = p.integer_alpha == 8 ? weigh(eighth_power) : weigh([&](double r) {
        return ratio_power(r, p.alpha, p.integer_alpha);
    });
    return {sum, std::log(sum) - p.alpha * std::log(d_star)};
}

using RowMatrixX4d = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;

// Runs query(k, found, term_over_d) for k in [0, count), each thread with buffers of its own,
// and returns the sum of the term counts it returns: in a region whose threads take `chunk`
// items at a time when `parallel`, else on the calling thread with no region (see
// kParallelThreshold). Each item writes results of its own, so the bits are the same either way.
template <typename Query>
std::size_t run_queries(std::size_t count, bool parallel, int chunk, Query&& query) {
    std::size_t pairs = 0;
    if (!parallel) {
        Neighbours found;
        std::vector<double> term_over_d;
        for (std::size_t k = 0; k < count; ++k) {
            pairs += query(k, found, term_over_d);
        }
        return pairs;
    }
#pragma omp parallel reduction(+ : pairs)
    {
        Neighbours found;
        std::vector<double> term_over_d;
#pragma omp for schedule(dynamic, chunk)
        for (std::size_t k = 0; k < count; ++k) {
            pairs += query(k, found, term_over_d);
        }
    }
    return pairs;
}

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
    const detail::PointGrid& grid = target.grid;
    // Queries in the cell order of their own grid: neighbouring queries share their terms
    // in cache.
    const std::size_t queries = source.active.size();
    // The query of one slot, with a thread's buffers; returns its number of terms.
    const auto query = [&](std::size_t slot, Neighbours& found, std::vector<double>& term_over_d) {
        const std::uint32_t i = source.point_at_slot[slot];
        const KeptTerms terms = weigh_terms(source, target, p, i, found, term_over_d);
        double s0 = 0;
        double sx = 0;
        double sy = 0;
        double sz = 0;
        for (std::size_t k = 0; k < found.count; ++k) {
            const double s = term_over_d[k];
            const Eigen::Vector3d y = grid.position(found.slots[k]);
            s0 += s;
            sx += s * y[0];
            sy += s * y[1];
            sz += s * y[2];
        }
        sums.log_f[i] = terms.log_f;
        sums.moments.row(i) = Eigen::RowVector4d(s0, sx, sy, sz) / terms.sum;
        return found.count;
    };
    sums.pairs = run_queries(queries, count > kParallelThreshold, 128, query);
    return sums;
}

// The target side's queries of a large evaluation run in this many contiguous stretches (in
// cell order), each scattering into rows of its own, which are then added stretch by stretch:
// the sums' order is the same for any thread count, and so are the results' bits. Eight keep
// eight cores busy; their rows cost 8 × 32 bytes per source point.
constexpr std::size_t kScatterStretches = 8;

// Buffers reused from one evaluation to the next: the moving side, and the target side's
// rows per stretch.
struct Workspace {
    Side source;                        // the moving side, refilled by each evaluation
    std::vector<RowMatrixX4d> coupled;  // per stretch, per source slot: the g-part's Σc, Σc·y
    std::vector<double> log_scale;      // per stretch: the common factor of its `coupled`
};

// The target side: g_j over the source, and the g-part of the coupling, which needs all of S
// (c_ij = S^{1/(2α)−1} a_i b_j d_ij^{−α−1} g_j^{−2} for that part) only through the common
// factor S^{1/(2α)−1}. Each query therefore scatters the rest, b_j/g_j · share_ji/d_ij, into
// its stretch's rows of the source slots (the queries run in cell order, so these rows stay
// in cache) and nothing per pair is kept. A stretch's rows share one factor exp(log_scale),
// set by its first query and raised when a later one would otherwise overflow.
struct TargetSums {
    Eigen::VectorXd log_g;
    std::size_t pairs = 0;
};

TargetSums sum_target(const Side& target, const Side& source, const Parameters& p,
                      Workspace& work) {
    const Eigen::Index count = target.points.rows();
    TargetSums sums{Eigen::VectorXd::Constant(count, kMinusInfinity), 0};
    const std::size_t stretches = count > kParallelThreshold ? kScatterStretches : 1;
    const auto source_slots = static_cast<Eigen::Index>(source.active.size());
    work.coupled.resize(stretches);
    work.log_scale.assign(stretches, kMinusInfinity);
    const std::size_t queries = target.active.size();  // in cell order, as in sum_source
    // The queries of one stretch, with a thread's buffers; returns their number of terms.
    const auto stretch_of_queries = [&](std::size_t stretch, Neighbours& found,
                                        std::vector<double>& term_over_d) {
        RowMatrixX4d& coupled = work.coupled[stretch];
        coupled.setZero(source_slots, 4);
        double& log_scale = work.log_scale[stretch];
        std::size_t terms_found = 0;
        const std::size_t end = queries * (stretch + 1) / stretches;
        for (std::size_t slot = queries * stretch / stretches; slot < end; ++slot) {
            const std::uint32_t j = target.point_at_slot[slot];
            const KeptTerms terms = weigh_terms(target, source, p, j, found, term_over_d);
            terms_found += found.count;
            sums.log_g[j] = terms.log_f;
            // b_j/g_j · share_ji/d_ij = exp(log b_j − log g_j − log Σt) · t_i/d_ij.
            const double log_factor = target.log_weight[j] - terms.log_f - std::log(terms.sum);
            if (log_scale == kMinusInfinity) {
                log_scale = log_factor;
            } else if (log_factor - log_scale > 300) {
                coupled *= std::exp(log_scale - log_factor);  // rare: far larger than before
                log_scale = log_factor;
            }
            const double factor = std::exp(log_factor - log_scale);
            const Eigen::RowVector3d y = target.points.row(j);
            for (std::size_t k = 0; k < found.count; ++k) {
                const double c = factor * term_over_d[k];
                const auto row = static_cast<Eigen::Index>(found.slots[k]);
                coupled(row, 0) += c;
                coupled.row(row).tail<3>() += c * y;
            }
        }
        return terms_found;
    };
    sums.pairs = run_queries(stretches, stretches > 1, 1, stretch_of_queries);
    return sums;
}

}  // namespace

namespace {

void check_options(const PseudoHausdorffOptions& options, const char* caller) {
    if (!detail::finite_at_least(options.alpha, 0.5)) {
        throw InvalidInput(std::string(caller) + ": alpha must be finite and >= 0.5, got " +
                           std::to_string(options.alpha));
    }
    // ε is a length and is squared as coordinates are: the same bound keeps ε² far from overflow.
    if (!detail::finite_above(options.epsilon, 0) || options.epsilon > kLargestCoordinate) {
        throw InvalidInput(std::string(caller) + ": epsilon must lie in (0, 1e50], got " +
                           std::to_string(options.epsilon));
    }
    if (!(options.moving_coverage >= 0 && options.moving_coverage <= 1)) {
        throw InvalidInput(std::string(caller) + ": moving_coverage must lie in [0, 1], got " +
                           std::to_string(options.moving_coverage));
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

// The descriptors' part of every pair's distance, |φ_u − ψ_j|², which the moving points'
// motion leaves unchanged: tabulated once per energy when there are at most this many pairs,
// else computed per pair and evaluation. That takes in the coarsest level of a match, whose
// guided flows take thousands of steps, and the refined one's (the TOSCA cat's 1,777 × 1,335
// pairs: its match 3 % faster than with up to 2^20), at most 64 MB per energy.
constexpr double kTabulatedPairs = 1 << 22;

struct DescriptorTable {
    RowMatrixXd by_moving;  // row: moving point u; column: the target point's slot
    RowMatrixXd by_target;  // row: target point j; column: moving point u

    // The same values add_descriptor_distances() would compute pair by pair, bit for bit.
    DescriptorTable(const Eigen::MatrixXd& moving_descriptors, const Side& target) {
        const RowMatrixXd moving = moving_descriptors;
        const auto slots = static_cast<Eigen::Index>(target.active.size());
        by_moving.resize(moving.rows(), slots);
        for (Eigen::Index u = 0; u < moving.rows(); ++u) {
            const auto phi = moving.row(u);
            for (Eigen::Index slot = 0; slot < slots; ++slot) {
                by_moving(u, slot) = (target.slot_descriptors.row(slot) - phi).squaredNorm();
            }
        }
        by_target = RowMatrixXd::Zero(target.points.rows(), moving.rows());
        for (Eigen::Index slot = 0; slot < slots; ++slot) {
            const std::uint32_t j = target.point_at_slot[static_cast<std::size_t>(slot)];
            by_target.row(j) = by_moving.col(slot).transpose();
        }
    }
};

struct PseudoHausdorffEnergy::Impl {
    Eigen::MatrixXd moving_descriptors;  // no columns without descriptors
    Side target;
    std::optional<DescriptorTable> table;  // for a moving mesh of moving_descriptors.rows()
    std::mutex cache_mutex;
    Eigen::MatrixX3d cached_V;
    Eigen::MatrixX3i cached_F;
    std::shared_ptr<const PseudoHausdorffEvaluation> cached;
    std::mutex workspace_mutex;
    Workspace workspace;

    Impl(const TriangleMesh& mesh, const PseudoHausdorffOptions& options,
         PointDescriptors descriptors)
        : moving_descriptors(std::move(descriptors.moving)),
          target(mesh.V, lumped_masses(mesh, MassType::Barycentric), options, descriptors.fixed) {
        if (target.has_descriptors() && static_cast<double>(moving_descriptors.rows()) *
                                                static_cast<double>(target.active.size()) <=
                                            kTabulatedPairs) {
            table.emplace(moving_descriptors, target);
            target.descriptor_table = &table->by_target;
            target.table_columns_by_slot = true;
        }
    }
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
        options.epsilon * options.epsilon, options.truncation, std::exp(600 / options.alpha)};

    const TargetSums g = sum_target(target, source, p, work);  // g_j over the source
    // f_i over the target, weighed by λ (none without the coverage term).
    const bool covered = options.moving_coverage > 0;
    const SourceSums f = covered ? sum_source(source, target, p) : SourceSums{};
    const double log_coverage = covered ? std::log(options.moving_coverage) : kMinusInfinity;

    // log S = LSE(log λ + log a_i − log f_i, log b_j − log g_j);
    // d_H = ε·expm1(log S/(2α) − log ε).
    std::vector<double> terms;
    terms.reserve(source.active.size() + target.active.size());
    for (const std::uint32_t i : source.active) {
        if (covered) {
            terms.push_back(log_coverage + source.log_weight[i] - f.log_f[i]);
        }
    }
    for (const std::uint32_t j : target.active) {
        terms.push_back(target.log_weight[j] - g.log_g[j]);
    }
    const double log_S = log_sum_exp(terms);

    PseudoHausdorffEvaluation result;
    result.value = options.epsilon * std::expm1(log_S / (2 * p.alpha) - std::log(options.epsilon));
    result.pairs = f.pairs + g.pairs;  // f.pairs: 0 without the coverage term

    // c_ij = S^{1/(2α)−1} a_i b_j d^{−α−1}(λ f_i^{−2} + g_j^{−2}), as f- and g-parts:
    // f-part = exp(base + log λ + log a_i − log f_i)·share_ij/d_ij, and symmetrically for g. The
    // coefficients are formed in the log domain: S^{1/(2α)−1} alone may overflow.
    const double base = (1 / (2 * p.alpha) - 1) * log_S;
    const Eigen::Index n = source.points.rows();
    const auto source_slots = static_cast<Eigen::Index>(source.active.size());
    // Per source point, the f-part and then each stretch's g-part times its common factor.
    std::vector<double> stretch_factor(work.coupled.size(), 0.0);
    for (std::size_t stretch = 0; stretch < work.coupled.size(); ++stretch) {
        if (work.log_scale[stretch] != kMinusInfinity) {
            stretch_factor[stretch] = std::exp(base + work.log_scale[stretch]);
        }  // else a stretch without queries
    }
    RowMatrixX4d accumulated = RowMatrixX4d::Zero(n, 4);  // Σc, Σc·y
    const auto accumulate = [&](Eigen::Index slot) {
        const std::uint32_t i = source.point_at_slot[static_cast<std::size_t>(slot)];
        Eigen::RowVector4d row =
            covered ? Eigen::RowVector4d(
                          std::exp(base + log_coverage + source.log_weight[i] - f.log_f[i]) *
                          f.moments.row(i))
                    : Eigen::RowVector4d::Zero();
        for (std::size_t stretch = 0; stretch < stretch_factor.size(); ++stretch) {
            if (stretch_factor[stretch] > 0) {
                row += stretch_factor[stretch] * work.coupled[stretch].row(slot);
            }
        }
        accumulated.row(i) = row;
    };
    for_each_index(source_slots, source_slots > kParallelLoopThreshold, accumulate);
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
    const Eigen::VectorXd masses = lumped_masses(mesh, MassType::Barycentric);
    // The buffers of the last evaluation (the moving side and its grid, the threads' rows) are
    // reused unless another thread is evaluating: fresh ones cost ~1 ms of page faults on a
    // 28K × 21K pair.
    std::unique_lock<std::mutex> lock(impl_->workspace_mutex, std::try_to_lock);
    Workspace own;
    Workspace& work = lock.owns_lock() ? impl_->workspace : own;
    work.source.assign(mesh.V, masses, options_, descriptors);
    work.source.descriptor_table = impl_->table ? &impl_->table->by_moving : nullptr;
    if (work.source.active.empty()) {
        throw InvalidInput("PseudoHausdorffEnergy::evaluate: mesh has zero area");
    }
    return evaluate_sides(work.source, impl_->target, options_, work);
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
