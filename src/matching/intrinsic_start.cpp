// SPDX-License-Identifier: MIT
#include "matching/intrinsic_start.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "genflow/matching/multiresolution.h"
#include "genflow/operators/area.h"
#include "genflow/operators/laplacian_eigenbasis.h"
#include "genflow/operators/normals.h"
#include "genflow/operators/volume.h"
#include "matching/functional_map.h"
#include "operators/triangle.h"
#include "spatial/point_index.h"
#include "spatial/surface_paths.h"

namespace genflow::detail {

namespace {

// The shapes are analysed at about this many vertices (all-pairs geodesics: 8 MB each).
constexpr Eigen::Index kVertices = 1000;

// Lengths are in units of √area, so that nothing depends on the shapes' scale. The measures
// below are on the coarsest levels of the 29 pairs of $GENFLOW_DATA (pairs.json and
// docs/eval/other_poses.json): the mean distance of the template's vertices, where the chosen
// map puts them, to their true places, over the target's diagonal.

// An extremity has the largest average geodesic distance within this radius: 5–12 per shape (a
// human's head, hands and feet; a cat's paws, tail, ears and muzzle); 0.1 found up to 46
// (fingers).
constexpr double kExtremityRadius = 0.15;
// Two geodesic distances (or two averages) within this fraction of the larger agree.
constexpr double kTolerance = 0.2;
// At most this many extremities per shape (the farthest on average): the clique search stays
// small on shapes with many bumps (a noisy scan).
constexpr std::size_t kMaxExtremities = 16;
// A bound on the clique search's steps (it never hangs, whatever the shapes).
constexpr long kCliqueSearchSteps = 200000;
// The most consistent landmark sets whose maps are compared by orientation, and how much less
// well than the best a map may keep it and still be kept for being more consistent: a
// quadruped's sets turned head to tail and left to right keep it as well as the right one
// (the Sumner horse: 0.78 and 0.77) and are less consistent (distances 1.4 times as far off).
// Margins of 0.05, 0.1 and 0.2: 4.81, 4.78 and 4.86 % on average.
constexpr std::size_t kCandidates = 8;
constexpr double kOrientationMargin = 0.1;

// The functional map: 20 eigenfunctions, Gaussians of three widths around each landmark, and
// the commutativity weight, for unit-area shapes (eigenvalues times the area). Measured with a
// prototype, weights 1e-2, 1e-4, 1e-6 and 1e-8 gave 12, 6, 4 and 4 % on TOSCA michael kneeling,
// 15, 14, 4 and 4 % on FAUST 000→001, 6.5, 3.8, 2.1 and 2.3 % on the makehuman body.
constexpr Eigen::Index kFunctions = 20;
constexpr std::array<double, 3> kWidths{0.15, 0.3, 0.6};
constexpr double kCommutativity = 1e-6;
// Gaussians of the distance are blind to a reflection: on a shape with one (a human's left and
// right), the map fitted to them may follow it in places and turn the surface over there
// (FAUST 000→001: orientation 0.05, where the right map's is 0.5). The turning functions of
// pairs of landmarks (turning_functions()) change sign under it and join the Gaussians with
// this weight. Median and mean: 0 3.4 and 4.8 %, 0.1 3.5 and 4.7 %, 0.2 3.1 and 4.6 %, 1
// worse (6.1 % on average: the functions are noisy near the landmarks). At 0.2, 1.9–4.5 % on
// 25 pairs, 8.7 % on the small TOSCA cat, 11 % on the libigl arm's pose 2 and 13 and 26 % on
// the libigl elephant's frames 200 and 300.
constexpr double kTurningWeight = 0.2;

bool agree(double a, double b) {
    return std::abs(a - b) <= kTolerance * std::max(a, b);
}

// What the start needs of one shape, at about kVertices vertices.
struct Shape {
    CoarseMesh coarse;
    Eigen::MatrixXd distance;  // geodesic, between all vertices (symmetric)
    Eigen::VectorXd average;   // each vertex's mean geodesic distance to the others
    std::vector<Eigen::Index> extremities;
    Eigen::MatrixXd functions;  // the lowest eigenfunctions, M-orthonormal at unit area
    Eigen::VectorXd masses;     // lumped, summing to 1
    Eigen::VectorXd values;     // the eigenvalues at unit area
    double unit = 1;            // √area
};

Shape analyse(const TriangleMesh& mesh) {
    Shape shape;
    shape.coarse = coarsen(mesh, kVertices);
    const TriangleMesh& coarse = shape.coarse.mesh;
    const double unit = std::sqrt(surface_area(coarse));
    shape.unit = unit;
    // Along the edges: chords would cut across the bends of a pose (spatial/surface_paths.h).
    const ChordGraph graph = chord_graph(coarse, 1);
    const Eigen::Index n = coarse.V.rows();
    shape.distance.resize(n, n);
#pragma omp parallel for schedule(dynamic, 16)
    for (Eigen::Index v = 0; v < n; ++v) {
        shape.distance.col(v) = path_lengths_from(graph, v) / unit;
    }
    // Between components (a scan's islands), as far as the farthest connected pair.
    const double farthest =
        (shape.distance.array() < kUnreachable).select(shape.distance, 0.0).maxCoeff();
    shape.distance = (shape.distance.array() < kUnreachable).select(shape.distance, farthest);
    shape.average = shape.distance.colwise().mean().transpose();

    for (Eigen::Index v = 0; v < n; ++v) {
        bool highest = true;
        for (Eigen::Index u = 0; u < n && highest; ++u) {
            highest = shape.distance(u, v) >= kExtremityRadius ||
                      shape.average(u) < shape.average(v) ||
                      (shape.average(u) == shape.average(v) && u >= v);
        }
        if (highest) {
            shape.extremities.push_back(v);
        }
    }
    std::sort(shape.extremities.begin(), shape.extremities.end(),
              [&](Eigen::Index a, Eigen::Index b) { return shape.average(a) > shape.average(b); });
    if (shape.extremities.size() > kMaxExtremities) {
        shape.extremities.resize(kMaxExtremities);
    }

    const LaplacianEigenbasis basis = laplacian_eigenbasis(coarse, kFunctions);
    shape.functions = unit * basis.functions;
    shape.masses = basis.masses / (unit * unit);
    shape.values = (unit * unit) * basis.values;
    return shape;
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
// their distances. (Sets one pair smaller as well let a wrong map in: FAUST 000→001, 4.1 % with
// the largest only, 39 % with them.)
std::vector<LandmarkSet> landmark_candidates(const Shape& from, const Shape& to) {
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

// Per vertex, for each pair (a, b) of `sources`, n · (∇d_a × ∇d_b): the sine of the angle
// from the way to a to the way to b, d the geodesic distance (piecewise linear, the gradients
// per face, averaged over the faces about a vertex by area). A reflection changes its sign.
Eigen::MatrixXd turning_functions(const Shape& shape, const std::vector<Eigen::Index>& sources) {
    const TriangleMesh& mesh = shape.coarse.mesh;
    const std::size_t count = sources.size();
    Eigen::MatrixXd result =
        Eigen::MatrixXd::Zero(mesh.V.rows(), static_cast<Eigen::Index>(count * (count - 1) / 2));
    Eigen::VectorXd weight = Eigen::VectorXd::Zero(mesh.V.rows());
    std::vector<Eigen::Vector3d> gradient(count);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const Triangle triangle(mesh, f);
        if (!(triangle.double_area > 0)) {
            continue;
        }
        const Eigen::Vector3d normal = triangle.cross / triangle.double_area;
        for (std::size_t s = 0; s < count; ++s) {
            gradient[s].setZero();
            for (int k = 0; k < 3; ++k) {
                const Eigen::Vector3d opposite = triangle.x[(k + 2) % 3] - triangle.x[(k + 1) % 3];
                gradient[s] += shape.distance(mesh.F(f, k), sources[s]) * normal.cross(opposite);
            }
            gradient[s] *= shape.unit / triangle.double_area;  // as on the shape of unit area
        }
        Eigen::Index column = 0;
        for (std::size_t a = 0; a < count; ++a) {
            for (std::size_t b = a + 1; b < count; ++b) {
                const double turning = normal.dot(gradient[a].cross(gradient[b]));
                for (int k = 0; k < 3; ++k) {
                    result(mesh.F(f, k), column) += triangle.double_area * turning;
                }
                ++column;
            }
        }
        for (int k = 0; k < 3; ++k) {
            weight(mesh.F(f, k)) += triangle.double_area;
        }
    }
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
        if (weight(v) > 0) {
            result.row(v) /= weight(v);
        }
    }
    return result;
}

// The target vertex of every template vertex by the functional map fitted to the landmarks:
// the Gaussians of the geodesic distance to each landmark and the turning functions of each
// pair of landmarks are to correspond (C a ≈ b for their coefficients), and C to commute with
// the Laplacians (C Λ ≈ Λ C), one row of C at a time: (B Bᵀ + w diag((λ_j − μ_r)²)) c_r = B a_r,
// with A, B the template's and the target's coefficients and λ, μ their eigenvalues.
std::vector<Eigen::Index> landmark_map(const Shape& from, const Shape& to, const LandmarkSet& set,
                                       Eigen::Index functions) {
    const auto gaussians = static_cast<Eigen::Index>(set.size() * kWidths.size());
    std::vector<Eigen::Index> from_sources;
    std::vector<Eigen::Index> to_sources;
    for (const LandmarkPair& pair : set) {
        from_sources.push_back(from.extremities[pair.from]);
        to_sources.push_back(to.extremities[pair.to]);
    }
    const Eigen::MatrixXd from_turning = turning_functions(from, from_sources);
    const Eigen::MatrixXd to_turning = turning_functions(to, to_sources);
    const Eigen::Index columns = gaussians + from_turning.cols();
    Eigen::MatrixXd from_descriptors(from.distance.rows(), columns);
    Eigen::MatrixXd to_descriptors(to.distance.rows(), columns);
    Eigen::Index column = 0;
    for (const LandmarkPair& pair : set) {
        for (const double width : kWidths) {
            from_descriptors.col(column) =
                (-(from.distance.col(from.extremities[pair.from]) / width).array().square()).exp();
            to_descriptors.col(column) =
                (-(to.distance.col(to.extremities[pair.to]) / width).array().square()).exp();
            ++column;
        }
    }
    from_descriptors.rightCols(from_turning.cols()) = kTurningWeight * from_turning;
    to_descriptors.rightCols(to_turning.cols()) = kTurningWeight * to_turning;
    const Eigen::MatrixXd A = from.functions.leftCols(functions).transpose() *
                              (from.masses.asDiagonal() * from_descriptors);
    const Eigen::MatrixXd B =
        to.functions.leftCols(functions).transpose() * (to.masses.asDiagonal() * to_descriptors);
    const Eigen::MatrixXd gram = B * B.transpose();
    Eigen::MatrixXd map(functions, functions);
    for (Eigen::Index r = 0; r < functions; ++r) {
        Eigen::MatrixXd system = gram;
        system.diagonal() +=
            kCommutativity * (to.values.head(functions).array() - from.values(r)).square().matrix();
        map.row(r) = system.ldlt().solve(B * A.row(r).transpose()).transpose();
    }
    return nearest_rows(from.functions.leftCols(functions) * map, to.functions.leftCols(functions));
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
    const Shape from = analyse(template_mesh);
    const Shape to = analyse(target);
    const std::vector<LandmarkSet> candidates = landmark_candidates(from, to);
    if (candidates.empty() || count == 0) {
        return {};
    }
    const Eigen::Index functions =
        std::min({kFunctions, from.functions.cols(), to.functions.cols()});
    const double facing = enclosed_volume(from.coarse.mesh) * enclosed_volume(to.coarse.mesh);
    const Eigen::MatrixX3d to_normals = (facing < 0 ? -1.0 : 1.0) * vertex_normals(to.coarse.mesh);

    std::vector<std::vector<Eigen::Index>> maps;
    std::vector<double> orientations;
    for (const LandmarkSet& set : candidates) {
        maps.push_back(landmark_map(from, to, set, functions));
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

    // Each template vertex goes where its nearest analysed vertex at rest goes (itself, for
    // the vertices the analysis kept).
    const PointIndex analysed(from.coarse.mesh.V);
    std::vector<Eigen::Index> analysed_vertex(static_cast<std::size_t>(template_mesh.V.rows()));
    for (Eigen::Index v = 0; v < template_mesh.V.rows(); ++v) {
        analysed_vertex[static_cast<std::size_t>(v)] =
            analysed.nearest(template_mesh.V.row(v).transpose()).first;
    }
    std::vector<IntrinsicStart> starts;
    for (std::size_t rank = 0; rank < order.size() && starts.size() < count; ++rank) {
        const std::size_t k = order[rank];
        IntrinsicStart start;
        start.orientation = orientations[k];
        start.landmarks = static_cast<int>(candidates[k].size());
        start.placement.resize(template_mesh.V.rows(), 3);
        for (Eigen::Index v = 0; v < template_mesh.V.rows(); ++v) {
            start.placement.row(v) = to.coarse.mesh.V.row(
                maps[k][static_cast<std::size_t>(analysed_vertex[static_cast<std::size_t>(v)])]);
        }
        const Eigen::Matrix4d fit =
            Eigen::umeyama(template_mesh.V.transpose(), start.placement.transpose(), true);
        const double scale = fit.block<3, 1>(0, 0).norm();
        if (!(scale > 0) || !fit.allFinite()) {
            continue;  // every vertex put on one point: no start to speak of
        }
        start.similarity.scale = scale;
        start.similarity.rotation = fit.topLeftCorner<3, 3>() / scale;
        start.similarity.translation = fit.topRightCorner<3, 1>();
        starts.push_back(std::move(start));
    }
    return starts;
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
