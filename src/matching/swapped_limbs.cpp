// SPDX-License-Identifier: MIT
#include "matching/swapped_limbs.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "genflow/exceptions.h"
#include "matching/intrinsic_start.h"
#include "spatial/point_index.h"

namespace genflow::detail {

namespace {

// The mean over the columns of the correlation, weighted by `masses`, of `from` and `to` (the
// template's turning functions and the target's pulled back); a column that vanishes on either
// side counts 0.
double mean_correlation(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to,
                        const Eigen::VectorXd& masses) {
    if (from.cols() == 0) {
        return 0;
    }
    double sum = 0;
    for (Eigen::Index c = 0; c < from.cols(); ++c) {
        const double both = (masses.array() * from.col(c).array() * to.col(c).array()).sum();
        const double first = (masses.array() * from.col(c).array().square()).sum();
        const double second = (masses.array() * to.col(c).array().square()).sum();
        if (first > 0 && second > 0) {
            sum += both / std::sqrt(first * second);
        }
    }
    return sum / static_cast<double>(from.cols());
}

// turning_agreement() with the template's turning functions computed once.
double agreement(const Eigen::MatrixXd& from_turning, const IntrinsicShape& from,
                 const IntrinsicShape& to, const std::vector<Eigen::Index>& correspondence,
                 const std::vector<Eigen::Index>& images) {
    const Eigen::MatrixXd pulled = turning_functions(to, images)(correspondence, Eigen::all);
    return mean_correlation(from_turning, pulled, from.masses);
}

// Two limbs are counterparts (a left one and a right one) if their extremities' average
// geodesic distances agree within this fraction of the larger: above what a left and a right
// limb differ by (up to 3.4 % measured), below what distinct limbs of one shape differ by (from
// 16 %; docs/measurements.md, "Swapped limbs").
constexpr double kCounterpartTolerance = 0.1;

bool counterparts(const IntrinsicShape& shape, std::size_t a, std::size_t b) {
    const double first = shape.average(shape.extremities[a]);
    const double second = shape.average(shape.extremities[b]);
    return std::abs(first - second) <= kCounterpartTolerance * std::max(first, second);
}

// Whether `vertex` of the target is within kExtremityRadius of one of its extremities: a match
// that swapped two limbs put each one's tip on the other's (within 0.10 at the coarsest levels
// of the three swapped results of docs/eval), not somewhere along a limb.
bool at_a_tip(const IntrinsicShape& shape, Eigen::Index vertex) {
    for (const Eigen::Index extremity : shape.extremities) {
        if (shape.distance(vertex, extremity) <= kExtremityRadius) {
            return true;
        }
    }
    return false;
}

}  // namespace

double turning_agreement(const IntrinsicShape& from, const IntrinsicShape& to,
                         const std::vector<Eigen::Index>& correspondence,
                         const std::vector<Eigen::Index>& images) {
    return agreement(turning_functions(from, from.extremities), from, to, correspondence, images);
}

LimbPlacement place_limbs(const IntrinsicShape& from, const IntrinsicShape& to,
                          const Eigen::MatrixX3d& deformed) {
    if (deformed.rows() != from.coarse.mesh.V.rows()) {
        throw InvalidInput("place_limbs: " + std::to_string(deformed.rows()) + " positions for " +
                           std::to_string(from.coarse.mesh.V.rows()) + " analysed vertices");
    }
    const PointIndex target_points(to.coarse.mesh.V);
    LimbPlacement placement;
    placement.correspondence.resize(static_cast<std::size_t>(deformed.rows()));
    for (Eigen::Index v = 0; v < deformed.rows(); ++v) {
        placement.correspondence[static_cast<std::size_t>(v)] =
            target_points.nearest(deformed.row(v).transpose()).first;
    }
    for (const Eigen::Index extremity : from.extremities) {
        placement.images.push_back(placement.correspondence[static_cast<std::size_t>(extremity)]);
    }
    placement.agreement = turning_agreement(from, to, placement.correspondence, placement.images);
    return placement;
}

SwappedLimbs find_swapped_limbs(const IntrinsicShape& from, const IntrinsicShape& to,
                                const LimbPlacement& match, double margin, double least_agreement) {
    SwappedLimbs swapped;
    swapped.images = match.images;
    swapped.agreement_before = match.agreement;
    swapped.agreement_after = match.agreement;
    const Eigen::MatrixXd from_turning = turning_functions(from, from.extremities);
    std::vector<Eigen::Index>& images = swapped.images;
    // Each exchange raises the agreement by more than the margin, so this ends; the bound
    // only says so.
    for (std::size_t round = 0; round < images.size(); ++round) {
        double best = swapped.agreement_after;
        std::pair<std::size_t, std::size_t> best_pair{0, 0};
        for (std::size_t a = 0; a < images.size(); ++a) {
            for (std::size_t b = a + 1; b < images.size(); ++b) {
                if (images[a] == images[b] || !counterparts(from, a, b) ||
                    !at_a_tip(to, images[a]) || !at_a_tip(to, images[b])) {
                    continue;
                }
                std::swap(images[a], images[b]);
                const double exchanged =
                    agreement(from_turning, from, to, match.correspondence, images);
                std::swap(images[a], images[b]);
                if (exchanged > best) {
                    best = exchanged;
                    best_pair = {a, b};
                }
            }
        }
        if (!(best > swapped.agreement_after + margin)) {
            break;
        }
        std::swap(images[best_pair.first], images[best_pair.second]);
        swapped.exchanged.push_back(best_pair);
        swapped.agreement_after = best;
    }
    if (swapped.agreement_after < least_agreement) {  // not a right map either: none believed
        swapped.exchanged.clear();
        swapped.images = match.images;
        swapped.agreement_after = swapped.agreement_before;
    }
    return swapped;
}

std::optional<Eigen::MatrixX3d> exchanged_placement(const TriangleMesh& template_mesh,
                                                    const IntrinsicShape& from,
                                                    const IntrinsicShape& to,
                                                    const SwappedLimbs& swapped) {
    if (swapped.exchanged.empty()) {
        return std::nullopt;
    }
    std::optional<IntrinsicStart> start = start_from_map(
        template_mesh, from, to, landmark_map(from, to, from.extremities, swapped.images));
    if (!start) {
        return std::nullopt;
    }
    return std::move(start->placement);
}

double exchange_drift(const IntrinsicShape& to, const SwappedLimbs& swapped,
                      const LimbPlacement& match) {
    double drift = 0;
    for (const auto& [a, b] : swapped.exchanged) {
        for (const std::size_t extremity : {a, b}) {
            drift =
                std::max(drift, to.distance(swapped.images[extremity], match.images[extremity]));
        }
    }
    return drift;
}

LimbPlacement limbs_placed(const AnalysedShapes& shapes, const Eigen::MatrixX3d& deformed) {
    const auto& [from, to] = shapes;
    return place_limbs(from, to, deformed(from.coarse.fine_vertex, Eigen::all));
}

}  // namespace genflow::detail
