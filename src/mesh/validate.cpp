// SPDX-License-Identifier: MIT
#include "genflow/mesh/validate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
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
    int face;
    std::uint8_t corner_lo;  // corner index (0..2) of lo in the face
    std::uint8_t corner_hi;
    bool forward;  // the face runs lo → hi
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

// A sliver test: whether a triangle's smallest angle is below `degrees`.
class SliverTest {
public:
    explicit SliverTest(double degrees)
        : degrees_(degrees),
          by_products_(degrees > 0 && degrees < 60),
          // tan of the limit, for a test by products that needs no atan2 (below).
          tan_limit_(by_products_ ? std::tan(degrees * std::numbers::pi / 180) : 0) {}

    // The smallest angle lies opposite the shortest edge (law of sines), at most 60°: its tan
    // is |u×v|/(u·v) > 0. Where that ratio is off the limit's tan by more than a relative 1e-9,
    // far above the rounding of either side, the products decide as atan2 would; near the limit
    // (and for limits of 60° or more, or none) atan2 decides.
    [[nodiscard]] bool operator()(const detail::Triangle& t) const {
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
        const double sine_part = u.cross(v).norm();
        const double cosine_part = u.dot(v);
        if (by_products_ && cosine_part > 0) {
            constexpr double kMargin = 1e-9;
            const double limit = tan_limit_ * cosine_part;
            if (sine_part > limit * (1 + kMargin)) {
                return false;
            }
            if (sine_part < limit * (1 - kMargin)) {
                return true;
            }
        }
        return std::atan2(sine_part, cosine_part) * 180 / std::numbers::pi < degrees_;
    }

private:
    double degrees_;
    bool by_products_;  // else atan2 decides every face
    double tan_limit_;
};

// The vertices' coordinates: non-finite ones, and ones too large for products of lengths.
struct VertexFindings {
    Tally non_finite{"vertex"};
    Tally huge{"vertex"};
};

VertexFindings check_vertices(const TriangleMesh& mesh) {
    VertexFindings found;
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        if (!std::isfinite(mesh.V(i, 0)) || !std::isfinite(mesh.V(i, 1)) ||
            !std::isfinite(mesh.V(i, 2))) {
            found.non_finite.add(i);
        } else if (mesh.V.row(i).cwiseAbs().maxCoeff() > kLargestCoordinate) {
            found.huge.add(i);
        }
    }
    return found;
}

// The faces' indices: out of range, repeated, the vertices no face uses, and the faces fit for
// the rest of the checks ("good").
struct IndexFindings {
    Tally out_of_range{"face"};
    Tally repeated{"face"};
    Tally unreferenced{"vertex"};
    std::vector<Eigen::Index> good_faces;
};

IndexFindings check_indices(const TriangleMesh& mesh) {
    const Eigen::Index n = mesh.V.rows();
    IndexFindings found;
    found.good_faces.reserve(static_cast<std::size_t>(mesh.F.rows()));
    std::vector<bool> referenced(static_cast<std::size_t>(n), false);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const int a = mesh.F(f, 0);
        const int b = mesh.F(f, 1);
        const int c = mesh.F(f, 2);
        if (std::min({a, b, c}) < 0 || std::max({a, b, c}) >= n) {
            found.out_of_range.add(f);
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            referenced[static_cast<std::size_t>(mesh.F(f, k))] = true;
        }
        if (a == b || b == c || c == a) {
            found.repeated.add(f);
            continue;
        }
        found.good_faces.push_back(f);
    }
    for (Eigen::Index i = 0; i < n; ++i) {
        if (!referenced[static_cast<std::size_t>(i)]) {
            found.unreferenced.add(i);
        }
    }
    return found;
}

// The good faces' shapes: zero area, and slivers.
struct ShapeFindings {
    Tally zero_area{"face"};
    Tally sliver{"face"};
};

ShapeFindings check_shapes(const TriangleMesh& mesh, const std::vector<Eigen::Index>& good_faces,
                           double sliver_angle_degrees) {
    ShapeFindings found;
    const SliverTest is_sliver(sliver_angle_degrees);
    for (const Eigen::Index f : good_faces) {
        const detail::Triangle t(mesh, f);
        if (t.degenerate()) {
            found.zero_area.add(f);
        } else if (is_sliver(t)) {
            found.sliver.add(f);
        }
    }
    return found;
}

// Extra copies of a face: the same vertex set more than once. The faces' sorted vertex triples
// (a, b, c) are counted into buckets by a, face by face, and each bucket's few sorted stably by
// (b, c): the order (a, b, c, face), in which a copy follows its first.
Tally duplicate_faces(const TriangleMesh& mesh, const std::vector<Eigen::Index>& good_faces) {
    struct SortedFace {
        std::array<int, 3> v;
        Eigen::Index face;
    };
    std::vector<SortedFace> sorted;
    sorted.reserve(good_faces.size());
    for (const Eigen::Index f : good_faces) {
        std::array<int, 3> v = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
        std::sort(v.begin(), v.end());
        sorted.push_back({v, f});
    }
    detail::sort_by_vertex(
        sorted, static_cast<std::size_t>(mesh.V.rows()),
        [](const SortedFace& face) { return face.v[0]; },
        [](const SortedFace& face) {
            return (static_cast<std::uint64_t>(face.v[1]) << 32) |
                   static_cast<std::uint32_t>(face.v[2]);
        });
    Tally duplicate{"face"};
    for (std::size_t k = 1; k < sorted.size(); ++k) {
        if (sorted[k - 1].v == sorted[k].v) {
            duplicate.add(sorted[k].face);
        }
    }
    return duplicate;
}

// The good faces' half-edges grouped by undirected edge, in the order (lo, hi, face): counted
// into buckets by lo face by face (so each bucket's traversals come by face), then each
// bucket's few sorted stably by hi.
std::vector<EdgeTraversal> grouped_half_edges(const TriangleMesh& mesh,
                                              const std::vector<Eigen::Index>& good_faces) {
    const auto for_each_traversal = [&](auto&& visit) {
        for (const Eigen::Index f : good_faces) {
            for (int k = 0; k < 3; ++k) {
                const int from = mesh.F(f, k);
                const int to = mesh.F(f, (k + 1) % 3);
                const auto k_from = static_cast<std::uint8_t>(k);
                const auto k_to = static_cast<std::uint8_t>((k + 1) % 3);
                const auto face = static_cast<int>(f);
                visit(from < to ? EdgeTraversal{from, to, face, k_from, k_to, true}
                                : EdgeTraversal{to, from, face, k_to, k_from, false});
            }
        }
    };
    return detail::items_by_vertex<EdgeTraversal>(
        static_cast<std::size_t>(mesh.V.rows()), for_each_traversal,
        [](const EdgeTraversal& edge) { return edge.lo; },
        [](const EdgeTraversal& edge) { return edge.hi; });
}

// The surface's topology over the good faces: edges, boundary, orientation, fans, components.
struct TopologyFindings {
    Tally non_manifold_edge{"edge"};
    Tally inconsistent{"edge"};
    Tally boundary{"edge"};
    Tally non_manifold_vertex{"vertex"};
    Eigen::Index edges = 0;
    Eigen::Index components = 0;
    Eigen::Index boundary_loops = 0;
    Eigen::Index vertices_in_faces = 0;
};

TopologyFindings check_topology(const TriangleMesh& mesh,
                                const std::vector<Eigen::Index>& good_faces) {
    const Eigen::Index n = mesh.V.rows();
    const std::vector<EdgeTraversal> half_edges = grouped_half_edges(mesh, good_faces);
    TopologyFindings found;
    // Corners (3f + k) are united across manifold edges: a vertex whose corners end in more than
    // one set has several fans, i.e. is non-manifold.
    detail::UnionFind corners(static_cast<std::size_t>(3 * mesh.F.rows()));
    detail::UnionFind vertex_sets(static_cast<std::size_t>(n));
    detail::UnionFind boundary_sets(static_cast<std::size_t>(n));
    std::vector<bool> on_boundary(static_cast<std::size_t>(n), false);
    for (std::size_t begin = 0; begin < half_edges.size();) {
        std::size_t end = begin;
        while (end < half_edges.size() && half_edges[end].lo == half_edges[begin].lo &&
               half_edges[end].hi == half_edges[begin].hi) {
            ++end;
        }
        const EdgeTraversal& first = half_edges[begin];
        ++found.edges;
        vertex_sets.unite(static_cast<std::size_t>(first.lo), static_cast<std::size_t>(first.hi));
        const std::size_t faces_on_edge = end - begin;
        if (faces_on_edge == 1) {
            found.boundary.add(first.lo, first.hi);
            boundary_sets.unite(static_cast<std::size_t>(first.lo),
                                static_cast<std::size_t>(first.hi));
            on_boundary[static_cast<std::size_t>(first.lo)] = true;
            on_boundary[static_cast<std::size_t>(first.hi)] = true;
        } else if (faces_on_edge == 2) {
            const EdgeTraversal& second = half_edges[begin + 1];
            if (first.forward == second.forward) {
                found.inconsistent.add(first.lo, first.hi);
            }
            const auto corner = [](const EdgeTraversal& edge, std::uint8_t k) {
                return 3 * static_cast<std::size_t>(edge.face) + k;
            };
            corners.unite(corner(first, first.corner_lo), corner(second, second.corner_lo));
            corners.unite(corner(first, first.corner_hi), corner(second, second.corner_hi));
        } else {
            found.non_manifold_edge.add(first.lo, first.hi);
        }
        begin = end;
    }

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
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto v = static_cast<std::size_t>(i);
        if (several_fans[v]) {
            found.non_manifold_vertex.add(i);
        }
        if (first_fan[v] != kNone) {
            ++found.vertices_in_faces;
            found.components += vertex_sets.find(v) == v ? 1 : 0;
        }
        if (on_boundary[v]) {
            found.boundary_loops += boundary_sets.find(v) == v ? 1 : 0;
        }
    }
    return found;
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
    const VertexFindings vertices = check_vertices(mesh);
    const IndexFindings indices = check_indices(mesh);
    const std::vector<Eigen::Index>& good_faces = indices.good_faces;
    // Shapes only where every coordinate is one that products of lengths take.
    const bool measurable = vertices.non_finite.count == 0 && vertices.huge.count == 0;
    const ShapeFindings shapes =
        measurable ? check_shapes(mesh, good_faces, options.sliver_angle_degrees) : ShapeFindings{};
    const Tally duplicate = duplicate_faces(mesh, good_faces);
    const TopologyFindings topology = check_topology(mesh, good_faces);
    const Tally& non_finite = vertices.non_finite;
    const Tally& huge = vertices.huge;
    const Tally& out_of_range = indices.out_of_range;
    const Tally& repeated = indices.repeated;
    const Tally& unreferenced = indices.unreferenced;
    const Tally& zero_area = shapes.zero_area;
    const Tally& sliver = shapes.sliver;
    const Tally& non_manifold_edge = topology.non_manifold_edge;
    const Tally& inconsistent = topology.inconsistent;
    const Tally& boundary = topology.boundary;
    const Tally& non_manifold_vertex = topology.non_manifold_vertex;
    r.non_finite_vertices = non_finite.count;
    r.huge_vertices = huge.count;
    r.out_of_range_faces = out_of_range.count;
    r.repeated_index_faces = repeated.count;
    r.zero_area_faces = zero_area.count;
    r.sliver_faces = sliver.count;
    r.unreferenced_vertices = unreferenced.count;
    r.duplicate_faces = duplicate.count;
    r.num_edges = topology.edges;
    r.non_manifold_edges = non_manifold_edge.count;
    r.inconsistent_orientation_edges = inconsistent.count;
    r.boundary_edges = boundary.count;
    r.non_manifold_vertices = non_manifold_vertex.count;
    r.components = topology.components;
    r.boundary_loops = topology.boundary_loops;
    r.euler_characteristic =
        topology.vertices_in_faces - r.num_edges + static_cast<Eigen::Index>(good_faces.size());
    if (r.manifold() && r.inconsistent_orientation_edges == 0 && !good_faces.empty()) {
        r.genus = (2 * r.components - r.boundary_loops - r.euler_characteristic) / 2;
    }
    if (r.closed() && r.manifold() && r.inconsistent_orientation_edges == 0 && measurable &&
        out_of_range.count == 0 && !good_faces.empty()) {
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
