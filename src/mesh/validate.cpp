// SPDX-License-Identifier: MIT
#include "genflow/mesh/validate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <tuple>
#include <utility>
#include <vector>

#include "genflow/operators/volume.h"
#include "mesh/sort_by_vertex.h"
#include "mesh/union_find.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

// One face's traversal of an undirected edge (lo, hi).
struct EdgeTraversal {
    int lo;
    int hi;
    bool forward;  // the face runs lo → hi
    Eigen::Index face;
    int corner_lo;  // corner index (0..2) of lo in the face
    int corner_hi;
};

// Counts a finding and remembers the first offender ("face 12", "edge 3-7") for the message.
class Tally {
public:
    explicit Tally(const char* item) : item_(item) {}

    void add(Eigen::Index index) {
        if (count++ == 0) {
            first = std::string(item_) + " " + std::to_string(index);
        }
    }
    void add(int lo, int hi) {
        if (count++ == 0) {
            first = std::string(item_) + " " + std::to_string(lo) + "-" + std::to_string(hi);
        }
    }

    Eigen::Index count = 0;
    std::string first;

private:
    const char* item_;
};

void report(std::vector<ValidationIssue>& issues, Severity severity, const Tally& tally,
            const std::string& what) {
    if (tally.count > 0) {
        issues.push_back(
            {severity, std::to_string(tally.count) + " " + what + " (first: " + tally.first + ")"});
    }
}

// The smallest angle lies opposite the shortest edge (law of sines): one atan2, not three.
double smallest_angle_degrees(const detail::Triangle& t) {
    int k = 0;  // the corner opposite the shortest edge, (k + 1, k + 2)
    double shortest = std::numeric_limits<double>::infinity();
    for (int c = 0; c < 3; ++c) {
        const double length2 = (t.x[(c + 2) % 3] - t.x[(c + 1) % 3]).squaredNorm();
        if (length2 < shortest) {
            shortest = length2;
            k = c;
        }
    }
    const Eigen::Vector3d u = t.x[(k + 1) % 3] - t.x[k];
    const Eigen::Vector3d v = t.x[(k + 2) % 3] - t.x[k];
    return std::atan2(u.cross(v).norm(), u.dot(v)) * 180 / std::numbers::pi;
}

}  // namespace

bool ValidationReport::ok() const {
    return std::none_of(issues.begin(), issues.end(), [](const ValidationIssue& issue) {
        return issue.severity == Severity::Error;
    });
}

std::string ValidationReport::first_error() const {
    for (const auto& issue : issues) {
        if (issue.severity == Severity::Error) {
            return issue.message;
        }
    }
    return {};
}

ValidationReport validate(const TriangleMesh& mesh, const ValidationOptions& options) {
    ValidationReport r;
    const Eigen::Index n = mesh.V.rows();
    const Eigen::Index m = mesh.F.rows();
    r.num_vertices = n;
    r.num_faces = m;

    Tally non_finite{"vertex"}, huge{"vertex"};
    for (Eigen::Index i = 0; i < n; ++i) {
        if (!std::isfinite(mesh.V(i, 0)) || !std::isfinite(mesh.V(i, 1)) ||
            !std::isfinite(mesh.V(i, 2))) {
            non_finite.add(i);
        } else if (mesh.V.row(i).cwiseAbs().maxCoeff() > kLargestCoordinate) {
            huge.add(i);
        }
    }
    r.non_finite_vertices = non_finite.count;
    r.huge_vertices = huge.count;

    // Per-face checks; collect the faces fit for topology.
    Tally out_of_range{"face"}, repeated{"face"}, zero_area{"face"}, sliver{"face"};
    std::vector<Eigen::Index> good_faces;
    good_faces.reserve(static_cast<std::size_t>(m));
    std::vector<bool> referenced(static_cast<std::size_t>(n), false);
    for (Eigen::Index f = 0; f < m; ++f) {
        const int a = mesh.F(f, 0);
        const int b = mesh.F(f, 1);
        const int c = mesh.F(f, 2);
        if (std::min({a, b, c}) < 0 || std::max({a, b, c}) >= n) {
            out_of_range.add(f);
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            referenced[static_cast<std::size_t>(mesh.F(f, k))] = true;
        }
        if (a == b || b == c || c == a) {
            repeated.add(f);
            continue;
        }
        good_faces.push_back(f);
        // Their geometry only where every coordinate is one that products of lengths take.
        if (non_finite.count == 0 && huge.count == 0) {
            const detail::Triangle t(mesh, f);
            if (t.degenerate()) {
                zero_area.add(f);
            } else if (smallest_angle_degrees(t) < options.sliver_angle_degrees) {
                sliver.add(f);
            }
        }
    }
    r.out_of_range_faces = out_of_range.count;
    r.repeated_index_faces = repeated.count;
    r.zero_area_faces = zero_area.count;
    r.sliver_faces = sliver.count;

    Tally unreferenced{"vertex"};
    for (Eigen::Index i = 0; i < n; ++i) {
        if (!referenced[static_cast<std::size_t>(i)]) {
            unreferenced.add(i);
        }
    }
    r.unreferenced_vertices = unreferenced.count;

    // Duplicate faces: the same vertex set more than once.
    std::vector<std::tuple<int, int, int, Eigen::Index>> sorted_faces;
    sorted_faces.reserve(good_faces.size());
    for (const Eigen::Index f : good_faces) {
        std::array<int, 3> v = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
        std::sort(v.begin(), v.end());
        sorted_faces.emplace_back(v[0], v[1], v[2], f);
    }
    detail::sort_by_vertex(
        sorted_faces, static_cast<std::size_t>(n),
        [](const auto& face) { return std::get<0>(face); }, std::less<>());
    Tally duplicate{"face"};
    for (std::size_t k = 1; k < sorted_faces.size(); ++k) {
        const auto& [a0, b0, c0, f0] = sorted_faces[k - 1];
        const auto& [a1, b1, c1, f1] = sorted_faces[k];
        if (a0 == a1 && b0 == b1 && c0 == c1) {
            duplicate.add(f1);
        }
    }
    r.duplicate_faces = duplicate.count;

    // Edges: group the half-edges of the good faces by undirected edge.
    std::vector<EdgeTraversal> half_edges;
    half_edges.reserve(3 * good_faces.size());
    for (const Eigen::Index f : good_faces) {
        for (int k = 0; k < 3; ++k) {
            const int from = mesh.F(f, k);
            const int to = mesh.F(f, (k + 1) % 3);
            const int k_to = (k + 1) % 3;
            if (from < to) {
                half_edges.push_back({from, to, true, f, k, k_to});
            } else {
                half_edges.push_back({to, from, false, f, k_to, k});
            }
        }
    }
    detail::sort_by_vertex(
        half_edges, static_cast<std::size_t>(n), [](const EdgeTraversal& edge) { return edge.lo; },
        [](const EdgeTraversal& x, const EdgeTraversal& y) {
            return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
        });

    // Corners (3f + k) are united across manifold edges: a vertex whose corners end in more than
    // one set has several fans, i.e. is non-manifold.
    detail::UnionFind corners(static_cast<std::size_t>(3 * m));
    detail::UnionFind vertex_sets(static_cast<std::size_t>(n));
    detail::UnionFind boundary_sets(static_cast<std::size_t>(n));
    std::vector<bool> on_boundary(static_cast<std::size_t>(n), false);
    Tally non_manifold_edge{"edge"}, inconsistent{"edge"}, boundary{"edge"};
    for (std::size_t begin = 0; begin < half_edges.size();) {
        std::size_t end = begin;
        while (end < half_edges.size() && half_edges[end].lo == half_edges[begin].lo &&
               half_edges[end].hi == half_edges[begin].hi) {
            ++end;
        }
        const EdgeTraversal& first = half_edges[begin];
        ++r.num_edges;
        vertex_sets.unite(static_cast<std::size_t>(first.lo), static_cast<std::size_t>(first.hi));
        const std::size_t faces_on_edge = end - begin;
        if (faces_on_edge == 1) {
            boundary.add(first.lo, first.hi);
            boundary_sets.unite(static_cast<std::size_t>(first.lo),
                                static_cast<std::size_t>(first.hi));
            on_boundary[static_cast<std::size_t>(first.lo)] = true;
            on_boundary[static_cast<std::size_t>(first.hi)] = true;
        } else if (faces_on_edge == 2) {
            const EdgeTraversal& second = half_edges[begin + 1];
            if (first.forward == second.forward) {
                inconsistent.add(first.lo, first.hi);
            }
            corners.unite(static_cast<std::size_t>(3 * first.face + first.corner_lo),
                          static_cast<std::size_t>(3 * second.face + second.corner_lo));
            corners.unite(static_cast<std::size_t>(3 * first.face + first.corner_hi),
                          static_cast<std::size_t>(3 * second.face + second.corner_hi));
        } else {
            non_manifold_edge.add(first.lo, first.hi);
        }
        begin = end;
    }
    r.non_manifold_edges = non_manifold_edge.count;
    r.inconsistent_orientation_edges = inconsistent.count;
    r.boundary_edges = boundary.count;

    // Fans per vertex: a vertex is non-manifold when its corners fall into more than one set.
    constexpr std::size_t kNone = static_cast<std::size_t>(-1);
    std::vector<std::size_t> first_fan(static_cast<std::size_t>(n), kNone);
    std::vector<bool> several_fans(static_cast<std::size_t>(n), false);
    for (const Eigen::Index f : good_faces) {
        for (int k = 0; k < 3; ++k) {
            const auto v = static_cast<std::size_t>(mesh.F(f, k));
            const std::size_t fan = corners.find(static_cast<std::size_t>(3 * f + k));
            if (first_fan[v] == kNone) {
                first_fan[v] = fan;
            } else if (first_fan[v] != fan) {
                several_fans[v] = true;
            }
        }
    }
    Tally non_manifold_vertex{"vertex"};
    std::vector<bool> has_face(static_cast<std::size_t>(n), false);
    for (Eigen::Index i = 0; i < n; ++i) {
        has_face[static_cast<std::size_t>(i)] = first_fan[static_cast<std::size_t>(i)] != kNone;
        if (several_fans[static_cast<std::size_t>(i)]) {
            non_manifold_vertex.add(i);
        }
    }
    r.non_manifold_vertices = non_manifold_vertex.count;

    Eigen::Index vertices_in_faces = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto v = static_cast<std::size_t>(i);
        if (has_face[v]) {
            ++vertices_in_faces;
            r.components += vertex_sets.find(v) == v ? 1 : 0;
        }
        if (on_boundary[v]) {
            r.boundary_loops += boundary_sets.find(v) == v ? 1 : 0;
        }
    }
    r.euler_characteristic =
        vertices_in_faces - r.num_edges + static_cast<Eigen::Index>(good_faces.size());
    if (r.manifold() && r.inconsistent_orientation_edges == 0 && !good_faces.empty()) {
        r.genus = (2 * r.components - r.boundary_loops - r.euler_characteristic) / 2;
    }
    if (r.closed() && r.manifold() && r.inconsistent_orientation_edges == 0 &&
        non_finite.count == 0 && huge.count == 0 && out_of_range.count == 0 &&
        !good_faces.empty()) {
        r.inward_oriented = enclosed_volume(mesh) < 0;
    }

    // Findings, errors first.
    auto& issues = r.issues;
    if (n == 0) {
        issues.push_back({Severity::Error, "mesh has no vertices"});
    }
    if (m == 0) {
        issues.push_back({Severity::Error, "mesh has no faces"});
    }
    report(issues, Severity::Error, non_finite, "vertices with non-finite coordinates");
    report(issues, Severity::Error, huge, "vertices with a coordinate beyond ±1e50");
    report(issues, Severity::Error, out_of_range, "faces with vertex indices out of range");
    // With no area at all there is no surface to measure, smooth or match.
    if (!good_faces.empty() && zero_area.count == static_cast<Eigen::Index>(good_faces.size())) {
        issues.push_back({Severity::Error, "every face has zero area"});
    }
    report(issues, Severity::Warning, repeated, "faces with a repeated vertex index");
    report(issues, Severity::Warning, zero_area, "zero-area faces");
    report(issues, Severity::Warning, sliver, "sliver faces");
    report(issues, Severity::Warning, duplicate, "duplicate faces");
    report(issues, Severity::Warning, non_manifold_edge, "non-manifold edges");
    report(issues, Severity::Warning, non_manifold_vertex, "non-manifold vertices");
    report(issues, Severity::Warning, inconsistent, "edges with inconsistent face orientation");
    report(issues, Severity::Warning, unreferenced, "unreferenced vertices");
    if (r.boundary_loops > 0) {
        issues.push_back({Severity::Warning, "open surface: " + std::to_string(r.boundary_edges) +
                                                 " boundary edges in " +
                                                 std::to_string(r.boundary_loops) +
                                                 " boundary loops"});
    }
    if (r.components > 1) {
        issues.push_back(
            {Severity::Warning, std::to_string(r.components) + " connected components"});
    }
    if (r.inward_oriented) {
        issues.push_back({Severity::Warning, "faces point inward (negative enclosed volume)"});
    }
    return r;
}

}  // namespace genflow
