// SPDX-License-Identifier: MIT
#include "genflow/matching/correspondence_error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <tuple>
#include <utility>

#include "genflow/exceptions.h"
#include "genflow/mesh/edges.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/spatial/closest_point.h"
#include "operators/triangle.h"
#include "spatial/farthest_points.h"
#include "spatial/surface_paths.h"

namespace genflow {

namespace {

// Landmarks for the path bounds, each a Dijkstra over the whole shape: more bound more pairs
// without a search but cost a Dijkstra each. 32 was the fastest on a good match, the common
// case; 64 halved the time only on a match gone wrong (docs/benchmarks.md, "Stranded vertices").
constexpr int kLandmarks = 32;

using detail::Chord;
using detail::ChordGraph;

// Lower and upper bounds on path lengths in the chord graph from a few landmark vertices
// (A*, landmarks and the triangle inequality: Goldberg and Harrelson, SODA 2005): d(a, b) is at
// least |d(l, a) − d(l, b)| and at most d(l, a) + d(l, b) for every landmark l, and at least
// |a − b|, as chords are straight. A vertex put on another limb is then decided without a
// search, and the others search towards where it was put: a bounded Dijkstra from every
// vertex of a match gone wrong walked most of the shape for each.
class Landmarks {
public:
    static constexpr double kFar = std::numeric_limits<double>::infinity();

    Landmarks(const TriangleMesh& mesh, const ChordGraph& graph, int count) : mesh_(mesh) {
        // Spread over the shape by farthest-point sampling in space (cheap, and the graph
        // distances are computed from them side by side below).
        const Eigen::Index n = mesh.V.rows();
        const std::vector<Eigen::Index> chosen = detail::farthest_points(mesh.V, 0, count);
        distance_.resize(n, static_cast<Eigen::Index>(chosen.size()));
#pragma omp parallel for schedule(dynamic, 1)
        for (std::ptrdiff_t l = 0; l < static_cast<std::ptrdiff_t>(chosen.size()); ++l) {
            distance_.col(l) =
                detail::path_lengths_from(graph, chosen[static_cast<std::size_t>(l)]);
        }
    }

    /// A lower bound on the path from vertex a to vertex b (+∞ across components).
    [[nodiscard]] double lower(Eigen::Index a, Eigen::Index b) const {
        double bound = (mesh_.V.row(a) - mesh_.V.row(b)).norm();
        for (Eigen::Index l = 0; l < distance_.cols(); ++l) {
            const double da = distance_(a, l);
            const double db = distance_(b, l);
            if (da == kFar || db == kFar) {
                if (da != db) {
                    return kFar;  // one reaches the landmark, the other does not
                }
                continue;
            }
            bound = std::max(bound, std::abs(da - db));
        }
        return bound;
    }

    /// An upper bound on the path from vertex a to vertex b (+∞ if no landmark reaches both).
    [[nodiscard]] double upper(Eigen::Index a, Eigen::Index b) const {
        return (distance_.row(a) + distance_.row(b)).minCoeff();
    }

private:
    const TriangleMesh& mesh_;
    Eigen::MatrixXd distance_;  // vertex × landmark
};

// Whether `point` (on face `face` of `mesh`) is within `bound` of vertex `source` along the
// surface: a path from the source to a corner of the face, plus the straight segment from that
// corner to the point, within the bound. Decided by the landmarks' bounds where they suffice,
// else by A* towards the face with their lower bound as the (consistent) estimate: it stops at
// the first such path, or once every path left is estimated longer than the bound.
// `distance_` holds +∞ for every vertex on entry and on return.
class BoundedPath {
public:
    BoundedPath(const TriangleMesh& mesh, const ChordGraph& graph, const Landmarks& landmarks)
        : mesh_(mesh),
          graph_(graph),
          landmarks_(landmarks),
          distance_(static_cast<std::size_t>(mesh.V.rows()), kFar) {}

    bool within(Eigen::Index source, Eigen::Index face, const Eigen::Vector3d& point,
                double bound) {
        std::array<Eigen::Index, 3> corner{};
        std::array<double, 3> corner_to_point{};
        for (int k = 0; k < 3; ++k) {
            corner[static_cast<std::size_t>(k)] = mesh_.F(face, k);
            corner_to_point[static_cast<std::size_t>(k)] =
                (mesh_.V.row(mesh_.F(face, k)).transpose() - point).norm();
        }
        // The estimate of the rest of the way from v: the shortest over the corners.
        const auto estimate = [&](Eigen::Index v) {
            double least = kFar;
            for (std::size_t k = 0; k < 3; ++k) {
                least = std::min(least, landmarks_.lower(v, corner[k]) + corner_to_point[k]);
            }
            return least;
        };
        double known = kFar;  // a path the landmarks vouch for
        for (std::size_t k = 0; k < 3; ++k) {
            known = std::min(known, landmarks_.upper(source, corner[k]) + corner_to_point[k]);
        }
        if (known <= bound) {
            return true;
        }
        const double first_estimate = estimate(source);
        if (first_estimate > bound) {
            return false;
        }
        // (path so far + estimate, path so far, vertex)
        using Entry = std::tuple<double, double, Eigen::Index>;
        std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
        queue.emplace(first_estimate, 0.0, source);
        set(source, 0.0);
        bool found = false;
        while (!queue.empty()) {
            const auto [f, d, v] = queue.top();
            queue.pop();
            if (f > bound) {
                break;  // every path left is estimated longer than the bound
            }
            if (d > distance_[static_cast<std::size_t>(v)]) {
                continue;  // reached since by a shorter path
            }
            for (std::size_t k = 0; k < 3; ++k) {
                if (v == corner[k] && d + corner_to_point[k] <= bound) {
                    found = true;
                }
            }
            if (found) {
                break;
            }
            for (const Chord& n : graph_[static_cast<std::size_t>(v)]) {
                const double through = d + n.length;
                if (through < distance_[static_cast<std::size_t>(n.vertex)]) {
                    const double ahead = through + estimate(n.vertex);
                    if (ahead <= bound) {
                        set(n.vertex, through);
                        queue.emplace(ahead, through, n.vertex);
                    }
                }
            }
        }
        for (const Eigen::Index v : touched_) {
            distance_[static_cast<std::size_t>(v)] = kFar;
        }
        touched_.clear();
        return found;
    }

private:
    static constexpr double kFar = std::numeric_limits<double>::infinity();
    const TriangleMesh& mesh_;
    const ChordGraph& graph_;
    const Landmarks& landmarks_;
    std::vector<double> distance_;
    std::vector<Eigen::Index> touched_;

    void set(Eigen::Index v, double d) {
        if (distance_[static_cast<std::size_t>(v)] == kFar) {
            touched_.push_back(v);
        }
        distance_[static_cast<std::size_t>(v)] = d;
    }
};

double median_of(Eigen::VectorXd values) {
    const Eigen::Index n = values.size();
    std::nth_element(values.data(), values.data() + n / 2, values.data() + n);
    const double upper = values[n / 2];
    if (n % 2 == 1) {
        return upper;
    }
    return 0.5 * (upper + *std::max_element(values.data(), values.data() + n / 2));
}

}  // namespace

CorrespondenceError correspondence_error(const Eigen::MatrixX3d& deformed,
                                         const TriangleMesh& truth,
                                         const StrandedOptions& options) {
    if (deformed.rows() != truth.V.rows()) {
        throw InvalidInput("correspondence_error: the deformed template has " +
                           std::to_string(deformed.rows()) + " vertices, the ground truth " +
                           std::to_string(truth.V.rows()));
    }
    if (deformed.rows() == 0 || !detail::all_finite(deformed)) {
        throw InvalidInput("correspondence_error: the deformed vertices must be finite and many");
    }
    if (!detail::finite_above(options.length, 0) || !detail::finite_at_least(options.detour, 1) ||
        !detail::finite_at_least(options.placement_tolerance, 0)) {
        throw InvalidInput(
            "correspondence_error: the stranded length must be > 0, the detour >= 1 and the "
            "placement tolerance >= 0");
    }
    const TriangleBvh bvh(truth);  // refuses a mesh without faces or with non-finite points
    const double diagonal = bounding_box_diagonal(truth);
    if (!(diagonal > 0)) {
        throw InvalidInput("correspondence_error: the ground truth has a zero bounding box");
    }
    CorrespondenceError error;
    error.distance = (deformed - truth.V).rowwise().norm() / diagonal;
    error.mean = error.distance.mean();
    error.median = median_of(error.distance);
    error.max = error.distance.maxCoeff();

    const double tolerance = options.placement_tolerance * mean_edge_length(truth);
    const ChordGraph graph = detail::chord_graph(truth, 2);
    const Landmarks landmarks(truth, graph, kLandmarks);
    // One byte per vertex: the threads write their own vertices, which std::vector<bool>'s
    // shared words would not allow.
    std::vector<char> stranded(static_cast<std::size_t>(deformed.rows()), 0);
#pragma omp parallel
    {
        BoundedPath path(truth, graph, landmarks);
#pragma omp for schedule(dynamic, 64)
        for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
            if ((deformed.row(i) - truth.V.row(i)).norm() <= tolerance) {
                continue;  // at its place, whichever part of the truth touches there
            }
            const SurfacePoint landed = bvh.closest_point(deformed.row(i).transpose());
            const double straight = (landed.point - truth.V.row(i).transpose()).norm();
            const double bound = std::max(options.length * diagonal, options.detour * straight);
            stranded[static_cast<std::size_t>(i)] =
                path.within(i, landed.face, landed.point, bound) ? 0 : 1;
        }
    }
    error.stranded.assign(stranded.begin(), stranded.end());
    error.stranded_count =
        static_cast<Eigen::Index>(std::count(stranded.begin(), stranded.end(), 1));

    // Faces turned over: a part put back to front near its own place (a hand palm for back)
    // moves few vertices far, so neither the mean nor the strands see it; its normals do.
    error.reversed.assign(static_cast<std::size_t>(truth.F.rows()), false);
    const TriangleMesh placed{deformed, truth.F};
    double total_area = 0;
    double reversed_area = 0;
    for (Eigen::Index f = 0; f < truth.F.rows(); ++f) {
        const detail::Triangle where_it_belongs(truth, f);
        total_area += where_it_belongs.area();
        if (detail::Triangle(placed, f).cross.dot(where_it_belongs.cross) < 0) {
            error.reversed[static_cast<std::size_t>(f)] = true;
            reversed_area += where_it_belongs.area();
            ++error.reversed_count;
        }
    }
    error.reversed_area = total_area > 0 ? reversed_area / total_area : 0;
    return error;
}

}  // namespace genflow
