// SPDX-License-Identifier: MIT
#include "genflow/mesh/repair.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <tuple>
#include <utility>

#include "genflow/exceptions.h"
#include "genflow/operators/area.h"
#include "mesh/union_find.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

using Faces = std::vector<std::array<Eigen::Index, 3>>;

Faces faces_of(const Eigen::MatrixX3i& F) {
    Faces faces(static_cast<std::size_t>(F.rows()));
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        faces[static_cast<std::size_t>(f)] = {F(f, 0), F(f, 1), F(f, 2)};
    }
    return faces;
}

bool repeats_a_vertex(const std::array<Eigen::Index, 3>& face) {
    return face[0] == face[1] || face[1] == face[2] || face[2] == face[0];
}

// Step 1 (and again after welding): faces with a repeated vertex removed.
Faces without_repeated_index_faces(const Faces& faces, Eigen::Index& removed) {
    Faces kept;
    kept.reserve(faces.size());
    for (const auto& face : faces) {
        if (repeats_a_vertex(face)) {
            ++removed;
        } else {
            kept.push_back(face);
        }
    }
    return kept;
}

// Step 2: per input vertex, the first vertex at identical coordinates (itself if none).
std::vector<Eigen::Index> welded_vertices(const Eigen::MatrixX3d& V, Eigen::Index& welded) {
    std::vector<Eigen::Index> order(static_cast<std::size_t>(V.rows()));
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    const auto coordinates = [&V](Eigen::Index v) {
        return std::array<double, 3>{V(v, 0), V(v, 1), V(v, 2)};
    };
    std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
        return coordinates(a) < coordinates(b);
    });
    std::vector<Eigen::Index> representative(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        const bool same = i > 0 && coordinates(order[i]) == coordinates(order[i - 1]);
        representative[static_cast<std::size_t>(order[i])] =
            same ? representative[static_cast<std::size_t>(order[i - 1])] : order[i];
        welded += same ? 1 : 0;
    }
    return representative;
}

// Step 3: extra copies of a face (the same vertex set) removed, the first kept.
Faces without_duplicate_faces(const Faces& faces, Eigen::Index& removed) {
    std::vector<std::pair<std::array<Eigen::Index, 3>, std::size_t>> keys(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
        keys[f] = {faces[f], f};
        std::sort(keys[f].first.begin(), keys[f].first.end());
    }
    std::sort(keys.begin(), keys.end());
    std::vector<bool> copy(faces.size(), false);
    for (std::size_t i = 1; i < keys.size(); ++i) {
        copy[keys[i].second] = keys[i].first == keys[i - 1].first;
    }
    Faces kept;
    kept.reserve(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
        if (copy[f]) {
            ++removed;
        } else {
            kept.push_back(faces[f]);
        }
    }
    return kept;
}

// Corner c of face f is number 3f + c. Two faces are joined across an edge when they are the
// only two on it (an edge of three or more faces joins none); their corners at the edge's
// ends are then in one fan of each end vertex.
detail::UnionFind fans_of_corners(const Faces& faces) {
    struct Side {
        Eigen::Index lo;
        Eigen::Index hi;
        std::size_t corner_lo;
        std::size_t corner_hi;
    };
    std::vector<Side> sides;
    sides.reserve(3 * faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
        for (std::size_t c = 0; c < 3; ++c) {
            const std::size_t d = (c + 1) % 3;
            const bool forward = faces[f][c] < faces[f][d];
            sides.push_back({std::min(faces[f][c], faces[f][d]), std::max(faces[f][c], faces[f][d]),
                             3 * f + (forward ? c : d), 3 * f + (forward ? d : c)});
        }
    }
    std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
        return std::tie(x.lo, x.hi) < std::tie(y.lo, y.hi);
    });
    detail::UnionFind fans(3 * faces.size());
    for (std::size_t i = 0; i < sides.size();) {
        std::size_t j = i;
        while (j < sides.size() && sides[j].lo == sides[i].lo && sides[j].hi == sides[i].hi) {
            ++j;
        }
        if (j - i == 2) {
            fans.unite(sides[i].corner_lo, sides[i + 1].corner_lo);
            fans.unite(sides[i].corner_hi, sides[i + 1].corner_hi);
        }
        i = j;
    }
    return fans;
}

// Step 4: every vertex whose corners form several fans split into one vertex per fan; the
// largest fan keeps the vertex. Appends the copies' sources to `source_vertex`.
void split_fans(Faces& faces, std::vector<Eigen::Index>& source_vertex, Eigen::Index& split) {
    detail::UnionFind fans = fans_of_corners(faces);
    // Corners grouped by vertex, then by fan.
    std::vector<std::tuple<Eigen::Index, std::size_t, std::size_t>> corners;  // vertex, fan, corner
    corners.reserve(3 * faces.size());
    for (std::size_t corner = 0; corner < 3 * faces.size(); ++corner) {
        corners.emplace_back(faces[corner / 3][corner % 3], fans.find(corner), corner);
    }
    std::sort(corners.begin(), corners.end());
    for (std::size_t i = 0; i < corners.size();) {
        const Eigen::Index v = std::get<0>(corners[i]);
        std::vector<std::pair<std::size_t, std::size_t>> fan_ranges;  // [begin, end) per fan
        std::size_t j = i;
        for (; j < corners.size() && std::get<0>(corners[j]) == v; ++j) {
            if (j == i || std::get<1>(corners[j]) != std::get<1>(corners[j - 1])) {
                fan_ranges.emplace_back(j, j);
            }
            fan_ranges.back().second = j + 1;
        }
        std::stable_sort(fan_ranges.begin(), fan_ranges.end(), [](const auto& x, const auto& y) {
            return x.second - x.first > y.second - y.first;
        });
        for (std::size_t fan = 1; fan < fan_ranges.size(); ++fan) {
            const auto copy = static_cast<Eigen::Index>(source_vertex.size());
            source_vertex.push_back(source_vertex[static_cast<std::size_t>(v)]);
            for (std::size_t k = fan_ranges[fan].first; k < fan_ranges[fan].second; ++k) {
                const std::size_t corner = std::get<2>(corners[k]);
                faces[corner / 3][corner % 3] = copy;
            }
            ++split;
        }
        i = j;
    }
}

// Step 5: the faces of the connected component with the largest area.
Faces largest_component(const Faces& faces, const Eigen::MatrixX3d& positions,
                        RepairCounts& counts) {
    detail::UnionFind components(faces.size());
    std::vector<std::size_t> a_face_of_vertex(static_cast<std::size_t>(positions.rows()),
                                              faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
        for (const Eigen::Index v : faces[f]) {
            std::size_t& first = a_face_of_vertex[static_cast<std::size_t>(v)];
            if (first == faces.size()) {
                first = f;
            }
            components.unite(first, f);
        }
    }
    std::vector<double> area(faces.size(), 0);
    double total = 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& face = faces[f];
        const Eigen::Vector3d e1 = positions.row(face[1]) - positions.row(face[0]);
        const Eigen::Vector3d e2 = positions.row(face[2]) - positions.row(face[0]);
        const double a = 0.5 * e1.cross(e2).norm();
        area[components.find(f)] += a;
        total += a;
    }
    std::size_t largest = components.find(0);
    Eigen::Index count = 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        if (components.find(f) == f) {
            ++count;
            largest = area[f] > area[largest] ? f : largest;
        }
    }
    counts.components_left_out = count - 1;
    counts.area_left_out = total > 0 ? 1 - area[largest] / total : 0;
    Faces kept;
    kept.reserve(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
        if (components.find(f) == largest) {
            kept.push_back(faces[f]);
        }
    }
    return kept;
}

// The surface of `faces` over the vertices they use, in the order of their first source
// vertex; fills `repaired.mesh`, `source_vertex` and `repaired_vertex`.
void compact(const Faces& faces, const Eigen::MatrixX3d& V,
             const std::vector<Eigen::Index>& source_of, RepairedSurface& repaired) {
    std::vector<Eigen::Index> used(source_of.size(), -1);
    for (const auto& face : faces) {
        for (const Eigen::Index v : face) {
            used[static_cast<std::size_t>(v)] = 0;
        }
    }
    // Originals first (in input order), then copies, so that an unchanged mesh keeps its order.
    Eigen::Index next = 0;
    for (std::size_t v = 0; v < used.size(); ++v) {
        if (used[v] == 0) {
            used[v] = next++;
        }
    }
    repaired.mesh.V.resize(next, 3);
    repaired.source_vertex.assign(static_cast<std::size_t>(next), -1);
    repaired.repaired_vertex.assign(static_cast<std::size_t>(V.rows()), -1);
    for (std::size_t v = 0; v < used.size(); ++v) {
        if (used[v] >= 0) {
            const Eigen::Index source = source_of[v];
            repaired.mesh.V.row(used[v]) = V.row(source);
            repaired.source_vertex[static_cast<std::size_t>(used[v])] = source;
            if (repaired.repaired_vertex[static_cast<std::size_t>(source)] < 0) {
                repaired.repaired_vertex[static_cast<std::size_t>(source)] = used[v];
            }
        }
    }
    repaired.mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t f = 0; f < faces.size(); ++f) {
        for (int c = 0; c < 3; ++c) {
            repaired.mesh.F(static_cast<Eigen::Index>(f), c) = static_cast<int>(
                used[static_cast<std::size_t>(faces[f][static_cast<std::size_t>(c)])]);
        }
    }
}

}  // namespace

bool RepairedSurface::changed() const {
    return counts.repeated_index_faces != 0 || counts.vertices_welded != 0 ||
           counts.duplicate_faces != 0 || counts.vertices_split != 0 ||
           counts.components_left_out != 0 || counts.unreferenced_vertices != 0;
}

std::string RepairedSurface::summary() const {
    std::vector<std::string> parts;
    const auto add = [&parts](Eigen::Index count, const std::string& what) {
        if (count > 0) {
            parts.push_back(what + " " + std::to_string(count));
        }
    };
    add(counts.repeated_index_faces, "removed faces with a repeated vertex:");
    add(counts.vertices_welded, "welded coincident vertices:");
    add(counts.duplicate_faces, "removed duplicate faces:");
    add(counts.vertices_split, "split non-manifold vertices:");
    if (counts.components_left_out > 0) {
        parts.push_back(
            "left out " + std::to_string(counts.components_left_out) + " smaller components (" +
            std::to_string(static_cast<int>(100 * counts.area_left_out + 0.5)) + " % of the area)");
    }
    add(counts.unreferenced_vertices, "vertices on no kept face:");
    std::string line;
    for (const std::string& part : parts) {
        line += (line.empty() ? "" : "; ") + part;
    }
    return line;
}

RepairedSurface repair_surface(const TriangleMesh& mesh, const RepairOptions& options) {
    detail::require_valid_mesh(mesh, "repair_surface");
    RepairedSurface repaired;
    RepairCounts& counts = repaired.counts;
    Faces faces = without_repeated_index_faces(faces_of(mesh.F), counts.repeated_index_faces);
    const std::vector<Eigen::Index> welded = welded_vertices(mesh.V, counts.vertices_welded);
    for (auto& face : faces) {
        for (Eigen::Index& v : face) {
            v = welded[static_cast<std::size_t>(v)];
        }
    }
    // Welding makes a face repeat a vertex where two of its corners coincided.
    faces = without_repeated_index_faces(faces, counts.repeated_index_faces);
    faces = without_duplicate_faces(faces, counts.duplicate_faces);
    if (faces.empty()) {
        throw InvalidInput("repair_surface: no face with three distinct vertices");
    }
    std::vector<Eigen::Index> source_vertex(static_cast<std::size_t>(mesh.V.rows()));
    std::iota(source_vertex.begin(), source_vertex.end(), Eigen::Index{0});
    split_fans(faces, source_vertex, counts.vertices_split);
    Eigen::MatrixX3d positions(static_cast<Eigen::Index>(source_vertex.size()), 3);
    for (std::size_t v = 0; v < source_vertex.size(); ++v) {
        positions.row(static_cast<Eigen::Index>(v)) = mesh.V.row(source_vertex[v]);
    }
    if (options.largest_component_only) {
        faces = largest_component(faces, positions, counts);
    }
    compact(faces, mesh.V, source_vertex, repaired);
    // A welded vertex is carried by the vertex it was welded into.
    for (std::size_t v = 0; v < welded.size(); ++v) {
        if (welded[v] != static_cast<Eigen::Index>(v)) {
            repaired.repaired_vertex[v] =
                repaired.repaired_vertex[static_cast<std::size_t>(welded[v])];
        }
    }
    counts.unreferenced_vertices = static_cast<Eigen::Index>(
        std::count(repaired.repaired_vertex.begin(), repaired.repaired_vertex.end(), -1));
    return repaired;
}

}  // namespace genflow
