// SPDX-License-Identifier: MIT
#include "matching/intrinsic_start.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "genflow/operators/normals.h"
#include "genflow/operators/volume.h"
#include "spatial/point_index.h"

namespace genflow::detail {

namespace {

// Lengths are in units of √area (IntrinsicShape). The measures below are on the coarsest levels
// of the 29 pairs of $GENFLOW_DATA (pairs.json and docs/eval/other_poses.json): the mean
// distance of the template's vertices, where the chosen map puts them, to their true places,
// over the target's diagonal.

// Two geodesic distances (or two averages) within this fraction of the larger agree.
constexpr double kTolerance = 0.2;
// A bound on the clique search's steps (it never hangs, whatever the shapes).
constexpr long kCliqueSearchSteps = 200000;
// The most consistent landmark sets whose maps are compared by orientation, and how much less
// well than the best a map may keep it and still be kept for being more consistent: a
// quadruped's sets turned head to tail and left to right keep it as well as the right one and
// are less consistent (docs/measurements.md, "Intrinsic start").
constexpr std::size_t kCandidates = 8;
constexpr double kOrientationMargin = 0.1;

bool agree(double a, double b) {
    return std::abs(a - b) <= kTolerance * std::max(a, b);
}

// A template extremity and the target extremity it is matched with (indices of `extremities`).
struct LandmarkPair {
    std::size_t from;
    std::size_t to;
};
using LandmarkSet = std::vector<LandmarkPair>;

// The maximal cliques of an association graph (Bron–Kerbosch with Tomita's pivot).
class CliqueSearch {
public:
    explicit CliqueSearch(std::vector<std::vector<bool>> adjacent)
        : adjacent_(std::move(adjacent)) {}

    std::vector<std::vector<std::size_t>> maximal_cliques() {
        std::vector<std::size_t> candidates(adjacent_.size());
        for (std::size_t k = 0; k < candidates.size(); ++k) {
            candidates[k] = k;
        }
        std::vector<std::size_t> clique;
        extend(clique, candidates, {});
        return std::move(cliques_);
    }

private:
    std::vector<std::vector<bool>> adjacent_;
    std::vector<std::vector<std::size_t>> cliques_;
    long steps_ = 0;

    std::vector<std::size_t> neighbours_in(const std::vector<std::size_t>& set,
                                           std::size_t node) const {
        std::vector<std::size_t> result;
        for (const std::size_t other : set) {
            if (adjacent_[node][other]) {
                result.push_back(other);
            }
        }
        return result;
    }

    void extend(std::vector<std::size_t>& clique, std::vector<std::size_t> candidates,
                std::vector<std::size_t> excluded) {
        if (++steps_ > kCliqueSearchSteps) {
            return;
        }
        if (candidates.empty()) {
            if (excluded.empty()) {
                cliques_.push_back(clique);
            }
            return;
        }
        // The pivot with the most candidate neighbours: its neighbours need not start a branch.
        std::size_t pivot = candidates.front();
        std::size_t most = 0;
        for (const std::vector<std::size_t>* set : {&candidates, &excluded}) {
            for (const std::size_t node : *set) {
                const std::size_t count = neighbours_in(candidates, node).size();
                if (count >= most) {
                    most = count;
                    pivot = node;
                }
            }
        }
        const std::vector<std::size_t> branches = [&] {
            std::vector<std::size_t> result;
            for (const std::size_t node : candidates) {
                if (!adjacent_[pivot][node]) {
                    result.push_back(node);
                }
            }
            return result;
        }();
        for (const std::size_t node : branches) {
            clique.push_back(node);
            extend(clique, neighbours_in(candidates, node), neighbours_in(excluded, node));
            clique.pop_back();
            candidates.erase(std::find(candidates.begin(), candidates.end(), node));
            excluded.push_back(node);
        }
    }
};

// The landmark sets to try, best first: the largest sets (at least 3) of extremity pairs whose
// averages agree and whose mutual geodesic distances agree, ranked by the mean disagreement of
// their distances. (Sets one pair smaller as well let wrong maps in.)
std::vector<LandmarkSet> landmark_candidates(const IntrinsicShape& from, const IntrinsicShape& to) {
    LandmarkSet nodes;
    for (std::size_t a = 0; a < from.extremities.size(); ++a) {
        for (std::size_t b = 0; b < to.extremities.size(); ++b) {
            if (agree(from.average(from.extremities[a]), to.average(to.extremities[b]))) {
                nodes.push_back({a, b});
            }
        }
    }
    const auto from_distance = [&](std::size_t a, std::size_t c) {
        return from.distance(from.extremities[a], from.extremities[c]);
    };
    const auto to_distance = [&](std::size_t b, std::size_t d) {
        return to.distance(to.extremities[b], to.extremities[d]);
    };
    std::vector<std::vector<bool>> adjacent(nodes.size(), std::vector<bool>(nodes.size()));
    for (std::size_t p = 0; p < nodes.size(); ++p) {
        for (std::size_t q = 0; q < nodes.size(); ++q) {
            adjacent[p][q] = nodes[p].from != nodes[q].from && nodes[p].to != nodes[q].to &&
                             agree(from_distance(nodes[p].from, nodes[q].from),
                                   to_distance(nodes[p].to, nodes[q].to));
        }
    }
    const std::vector<std::vector<std::size_t>> cliques =
        CliqueSearch(std::move(adjacent)).maximal_cliques();
    std::size_t largest = 3;
    for (const std::vector<std::size_t>& clique : cliques) {
        largest = std::max(largest, clique.size());
    }
    std::vector<std::pair<double, LandmarkSet>> ranked;
    for (const std::vector<std::size_t>& clique : cliques) {
        if (clique.size() < largest) {
            continue;
        }
        LandmarkSet set;
        double disagreement = 0;
        for (const std::size_t p : clique) {
            for (const std::size_t q : clique) {
                disagreement += std::abs(from_distance(nodes[p].from, nodes[q].from) -
                                         to_distance(nodes[p].to, nodes[q].to));
            }
            set.push_back(nodes[p]);
        }
        ranked.emplace_back(disagreement, std::move(set));
    }
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<LandmarkSet> result;
    for (std::size_t k = 0; k < std::min(kCandidates, ranked.size()); ++k) {
        result.push_back(std::move(ranked[k].second));
    }
    return result;
}

// IntrinsicStart::orientation of a correspondence between the coarse shapes; `to_normals` are
// the target's vertex normals, turned to face as the template's do (outwards if it is closed).
double orientation(const TriangleMesh& from, const TriangleMesh& to,
                   const Eigen::MatrixX3d& to_normals,
                   const std::vector<Eigen::Index>& correspondence) {
    double sum = 0;
    double magnitude = 0;
    for (Eigen::Index f = 0; f < from.F.rows(); ++f) {
        std::array<Eigen::Index, 3> image{};
        for (int k = 0; k < 3; ++k) {
            image[static_cast<std::size_t>(k)] =
                correspondence[static_cast<std::size_t>(from.F(f, k))];
        }
        const Eigen::Vector3d a = to.V.row(image[0]);
        const Eigen::Vector3d normal = (Eigen::Vector3d(to.V.row(image[1])) - a)
                                           .cross(Eigen::Vector3d(to.V.row(image[2])) - a);
        const double along = normal.dot(
            (to_normals.row(image[0]) + to_normals.row(image[1]) + to_normals.row(image[2]))
                .transpose());
        sum += along;
        magnitude += std::abs(along);
    }
    return magnitude > 0 ? sum / magnitude : 0;
}

}  // namespace

std::vector<IntrinsicStart> intrinsic_starts(const TriangleMesh& template_mesh,
                                             const TriangleMesh& target, std::size_t count) {
    const AnalysedShapes shapes = analysed_shapes(nullptr, template_mesh, target);
    return intrinsic_starts(template_mesh, shapes.first, shapes.second, count);
}

std::vector<IntrinsicStart> intrinsic_starts(const TriangleMesh& template_mesh,
                                             const IntrinsicShape& from, const IntrinsicShape& to,
                                             std::size_t count) {
    const std::vector<LandmarkSet> candidates = landmark_candidates(from, to);
    if (candidates.empty() || count == 0) {
        return {};
    }
    const double facing = enclosed_volume(from.coarse.mesh) * enclosed_volume(to.coarse.mesh);
    const Eigen::MatrixX3d to_normals = (facing < 0 ? -1.0 : 1.0) * vertex_normals(to.coarse.mesh);

    std::vector<std::vector<Eigen::Index>> maps;
    std::vector<double> orientations;
    for (const LandmarkSet& set : candidates) {
        std::vector<Eigen::Index> from_sources;
        std::vector<Eigen::Index> to_sources;
        for (const LandmarkPair& pair : set) {
            from_sources.push_back(from.extremities[pair.from]);
            to_sources.push_back(to.extremities[pair.to]);
        }
        maps.push_back(landmark_map(from, to, from_sources, to_sources));
        orientations.push_back(
            orientation(from.coarse.mesh, to.coarse.mesh, to_normals, maps.back()));
    }
    // The preferred set: the most consistent of those that keep the orientation about as well
    // as the best; then the others, the best kept orientation first.
    const double most = *std::max_element(orientations.begin(), orientations.end());
    std::size_t preferred = 0;
    while (orientations[preferred] < most - kOrientationMargin) {
        ++preferred;
    }
    std::vector<std::size_t> order{preferred};
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        if (k != preferred) {
            order.push_back(k);
        }
    }
    std::stable_sort(order.begin() + 1, order.end(), [&](std::size_t a, std::size_t b) {
        return orientations[a] > orientations[b];
    });

    std::vector<IntrinsicStart> starts;
    for (std::size_t rank = 0; rank < order.size() && starts.size() < count; ++rank) {
        const std::size_t k = order[rank];
        std::optional<IntrinsicStart> start = start_from_map(template_mesh, from, to, maps[k]);
        if (start) {  // else every vertex is put on one point: no start to speak of
            start->orientation = orientations[k];
            start->landmarks = static_cast<int>(candidates[k].size());
            starts.push_back(std::move(*start));
        }
    }
    return starts;
}

std::optional<IntrinsicStart> start_from_map(const TriangleMesh& template_mesh,
                                             const IntrinsicShape& from, const IntrinsicShape& to,
                                             const std::vector<Eigen::Index>& map) {
    // Each template vertex goes where its nearest analysed vertex at rest goes (itself, for
    // the vertices the analysis kept).
    const PointIndex analysed(from.coarse.mesh.V);
    IntrinsicStart start;
    start.placement.resize(template_mesh.V.rows(), 3);
    for (Eigen::Index v = 0; v < template_mesh.V.rows(); ++v) {
        const Eigen::Index nearest = analysed.nearest(template_mesh.V.row(v).transpose()).first;
        start.placement.row(v) = to.coarse.mesh.V.row(map[static_cast<std::size_t>(nearest)]);
    }
    const Eigen::RowVector3d centre = start.placement.colwise().mean();
    if (!((start.placement.rowwise() - centre).squaredNorm() > 0)) {
        return std::nullopt;
    }
    // The scale from the areas, which bending keeps (as the rigid starts'), and the rotation
    // and translation that fit the placement best at that scale. A least-squares similarity
    // would shrink the template to fit a pose folded onto itself (a kneeling figure took a
    // standing one at half its size).
    const double scale = to.unit / from.unit;
    const Eigen::Matrix4d fit =
        Eigen::umeyama(scale * template_mesh.V.transpose(), start.placement.transpose(), false);
    if (!(scale > 0) || !fit.allFinite()) {
        return std::nullopt;
    }
    start.similarity.scale = scale;
    start.similarity.rotation = fit.topLeftCorner<3, 3>();
    start.similarity.translation = fit.topRightCorner<3, 1>();
    return start;
}

void rescale(IntrinsicStart& start, const TriangleMesh& template_mesh, double scale) {
    // The least-squares rotation between centred point sets does not depend on their scales.
    const Eigen::Vector3d template_centre = template_mesh.V.colwise().mean().transpose();
    const Eigen::Vector3d placement_centre = start.placement.colwise().mean().transpose();
    start.similarity.scale = scale;
    start.similarity.translation =
        placement_centre - scale * start.similarity.rotation * template_centre;
}

std::optional<IntrinsicStart> intrinsic_start(const TriangleMesh& template_mesh,
                                              const TriangleMesh& target) {
    std::vector<IntrinsicStart> starts = intrinsic_starts(template_mesh, target, 1);
    if (starts.empty()) {
        return std::nullopt;
    }
    return std::move(starts.front());
}

}  // namespace genflow::detail
