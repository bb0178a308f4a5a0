// SPDX-License-Identifier: MIT
#include "genflow/spatial/point_cloud_surface.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/mesh/boundary_loops.h"
#include "operators/triangle.h"
#include "spatial/point_index.h"

namespace genflow {

namespace {

using Face = std::array<Eigen::Index, 3>;

// The tangent plane is fitted to a point and its nearest six, the first ring of a regular
// sampling: where the surface curves within the farther neighbours (a finger), they would tilt
// it.
constexpr std::size_t kPlaneNeighbours = 6;

// Per point, the earlier point at the same coordinates, or the point itself.
std::vector<Eigen::Index> first_copies(const Eigen::MatrixX3d& points) {
    std::vector<Eigen::Index> order(static_cast<std::size_t>(points.rows()));
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    const auto row = [&](Eigen::Index i) {
        return std::array{points(i, 0), points(i, 1), points(i, 2)};
    };
    std::stable_sort(order.begin(), order.end(),
                     [&](Eigen::Index a, Eigen::Index b) { return row(a) < row(b); });
    std::vector<Eigen::Index> first(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
        const bool copy = k > 0 && row(order[k]) == row(order[k - 1]);
        first[static_cast<std::size_t>(order[k])] =
            copy ? first[static_cast<std::size_t>(order[k - 1])] : order[k];
    }
    return first;
}

// The plane of least variance of `p` and its neighbours: (u, v, n) as columns, right-handed.
Eigen::Matrix3d tangent_frame(const Eigen::MatrixX3d& points, Eigen::Index p,
                              const std::vector<Eigen::Index>& neighbours) {
    Eigen::MatrixX3d local(static_cast<Eigen::Index>(neighbours.size()) + 1, 3);
    local.row(0) = points.row(p);
    for (std::size_t k = 0; k < neighbours.size(); ++k) {
        local.row(static_cast<Eigen::Index>(k) + 1) = points.row(neighbours[k]);
    }
    const Eigen::MatrixX3d centred = local.rowwise() - local.colwise().mean();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(centred.transpose() * centred);
    Eigen::Matrix3d frame;
    frame.col(2) = solver.eigenvectors().col(0);  // least variance: the normal
    frame.col(0) = solver.eigenvectors().col(2);
    frame.col(1) = frame.col(2).cross(frame.col(0));
    return frame;
}

// A point's nearest neighbours (copies left out, nearest first) and its tangent frame.
struct Neighbourhood {
    std::vector<Eigen::Index> nearest;
    Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
};

// The frame square to a given normal: (u, v, n), right-handed.
Eigen::Matrix3d frame_about(const Eigen::Vector3d& normal) {
    Eigen::Matrix3d frame;
    frame.col(2) = normal.normalized();
    frame.col(0) = frame.col(2).unitOrthogonal();
    frame.col(1) = frame.col(2).cross(frame.col(0));
    return frame;
}

// With `normals` (rows; none: estimated), a neighbour whose normal points against the point's
// is on another sheet facing it across a gap narrower than the sampling (an arm against the
// torso) and is left out, and the frame is square to the point's own normal.
Neighbourhood neighbourhood_of(const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& normals,
                               Eigen::Index p, const detail::PointIndex& index,
                               const std::vector<Eigen::Index>& first, int count) {
    std::vector<std::pair<std::uint32_t, double>> found;
    index.nearest(points.row(p).transpose(), static_cast<std::size_t>(count) + 1, found);
    const bool given = normals.rows() > 0;
    Neighbourhood hood;
    for (const auto& [j, distance_squared] : found) {
        const auto q = static_cast<Eigen::Index>(j);
        if (distance_squared > 0 && first[static_cast<std::size_t>(q)] == q &&
            (!given || normals.row(p).dot(normals.row(q)) > 0)) {
            hood.nearest.push_back(q);
        }
    }
    if (given) {
        hood.frame = frame_about(normals.row(p).transpose());
        return hood;
    }
    const auto plane_count =
        static_cast<std::ptrdiff_t>(std::min(hood.nearest.size(), kPlaneNeighbours));
    hood.frame =
        tangent_frame(points, p, {hood.nearest.begin(), hood.nearest.begin() + plane_count});
    return hood;
}

// A point's neighbours laid out on its tangent plane.
struct TangentNeighbours {
    std::vector<Eigen::Index> index;
    std::vector<Eigen::Vector2d> at;
    double radius = 0;  // 3D distance of the farthest neighbour
};

// Each neighbour is laid out in the direction of its projection on the tangent plane, at its
// own distance from the point (the neighbourhood rolled out, not flattened): a projection would
// bring the far neighbours closer where the surface curves, and the Delaunay choice rests on the
// distances.
TangentNeighbours laid_out(const Eigen::MatrixX3d& points, Eigen::Index p,
                           const Neighbourhood& hood) {
    TangentNeighbours result;
    for (const Eigen::Index q : hood.nearest) {
        const Eigen::Vector3d offset = (points.row(q) - points.row(p)).transpose();
        const Eigen::Vector2d along(offset.dot(hood.frame.col(0)), offset.dot(hood.frame.col(1)));
        if (along.squaredNorm() > 0) {  // straight above the point: no direction in the plane
            result.index.push_back(q);
            result.at.emplace_back(along.normalized() * offset.norm());
            result.radius = std::max(result.radius, offset.norm());
        }
    }
    return result;
}

// A corner of a point's Voronoi cell in its tangent plane, and the neighbour whose bisector
// carries the cell's edge that leaves it (−1: the bounding box's).
struct CellCorner {
    Eigen::Vector2d at;
    Eigen::Index side;
};

// `cell` (counter-clockwise) cut to the side of the bisector between the origin and `q` that
// holds the origin (Sutherland–Hodgman); the new edge is `side`'s.
std::vector<CellCorner> clip(const std::vector<CellCorner>& cell, const Eigen::Vector2d& q,
                             Eigen::Index side) {
    const double limit = q.squaredNorm() / 2;
    const auto inside = [&](const Eigen::Vector2d& x) { return x.dot(q) <= limit; };
    std::vector<CellCorner> clipped;
    for (std::size_t t = 0; t < cell.size(); ++t) {
        const CellCorner& a = cell[t];
        const CellCorner& b = cell[(t + 1) % cell.size()];
        const bool a_in = inside(a.at);
        if (a_in) {
            clipped.push_back(a);
        }
        if (a_in != inside(b.at)) {
            const double s = (limit - a.at.dot(q)) / (b.at - a.at).dot(q);
            clipped.push_back({a.at + s * (b.at - a.at), a_in ? side : a.side});
        }
    }
    return clipped;
}

// The Delaunay triangles around `p` among its tangent neighbours, counter-clockwise about its
// tangent frame's normal: consecutive edges of its Voronoi cell whose shared corner (the
// triangle's circumcentre) lies within the neighbours' radius.
std::vector<Face> delaunay_fan(Eigen::Index p, const TangentNeighbours& neighbours) {
    const double box = 2 * neighbours.radius;
    std::vector<CellCorner> cell = {
        {{-box, -box}, -1}, {{box, -box}, -1}, {{box, box}, -1}, {{-box, box}, -1}};
    for (std::size_t k = 0; k < neighbours.index.size(); ++k) {
        cell = clip(cell, neighbours.at[k], static_cast<Eigen::Index>(k));
    }
    std::vector<Face> fan;
    for (std::size_t t = 0; t < cell.size(); ++t) {
        const CellCorner& next = cell[(t + 1) % cell.size()];
        if (cell[t].side >= 0 && next.side >= 0 && next.at.norm() <= neighbours.radius) {
            fan.push_back({p, neighbours.index[static_cast<std::size_t>(cell[t].side)],
                           neighbours.index[static_cast<std::size_t>(next.side)]});
        }
    }
    return fan;
}

// A face as one of its fans orients it, and how many of its corners' fans hold it.
struct Vote {
    Face face;
    int count = 0;
};

// Every point's neighbourhood (copies of an earlier point have none).
std::vector<Neighbourhood> neighbourhoods(const Eigen::MatrixX3d& points,
                                          const Eigen::MatrixX3d& normals,
                                          const std::vector<Eigen::Index>& first, int count) {
    const detail::PointIndex index(points);
    std::vector<Neighbourhood> hoods(static_cast<std::size_t>(points.rows()));
    for (Eigen::Index p = 0; p < points.rows(); ++p) {
        if (first[static_cast<std::size_t>(p)] == p) {
            hoods[static_cast<std::size_t>(p)] =
                neighbourhood_of(points, normals, p, index, first, count);
        }
    }
    return hoods;
}

// Per triangle of the fans (its corners sorted), its vote.
std::map<Face, Vote> votes_of_fans(const Eigen::MatrixX3d& points,
                                   const std::vector<Neighbourhood>& hoods) {
    std::map<Face, Vote> votes;
    for (Eigen::Index p = 0; p < points.rows(); ++p) {
        const Neighbourhood& hood = hoods[static_cast<std::size_t>(p)];
        if (hood.nearest.empty()) {
            continue;
        }
        for (const Face& face : delaunay_fan(p, laid_out(points, p, hood))) {
            Face key = face;
            std::sort(key.begin(), key.end());
            Vote& vote = votes[key];
            vote.face = face;
            ++vote.count;
        }
    }
    return votes;
}

// Turns the normals so that neighbours' agree, along the neighbours whose planes are the most
// alike first (a minimum spanning tree of the neighbour graph weighted 1 − |n_p·n_q|, after
// Hoppe et al. 1992): the sign travels through flat regions before it crosses a crease, and
// across the gaps between the faces' components.
std::vector<Eigen::Vector3d> oriented_normals(const std::vector<Neighbourhood>& hoods) {
    std::vector<Eigen::Vector3d> normal(hoods.size());
    std::vector<std::vector<std::size_t>> adjacent(hoods.size());
    for (std::size_t p = 0; p < hoods.size(); ++p) {
        normal[p] = hoods[p].frame.col(2);
        for (const Eigen::Index q : hoods[p].nearest) {
            adjacent[p].push_back(static_cast<std::size_t>(q));
            adjacent[static_cast<std::size_t>(q)].push_back(p);
        }
    }
    std::vector<bool> reached(hoods.size(), false);
    using Step = std::tuple<double, std::size_t, std::size_t>;  // weight, from, to
    std::priority_queue<Step, std::vector<Step>, std::greater<>> frontier;
    for (std::size_t seed = 0; seed < hoods.size(); ++seed) {
        frontier.emplace(0.0, seed, seed);
        while (!frontier.empty()) {
            const auto [weight, from, to] = frontier.top();
            frontier.pop();
            if (reached[to]) {
                continue;
            }
            reached[to] = true;
            if (normal[from].dot(normal[to]) < 0) {
                normal[to] = -normal[to];
            }
            for (const std::size_t next : adjacent[to]) {
                if (!reached[next]) {
                    frontier.emplace(1 - std::abs(normal[to].dot(normal[next])), to, next);
                }
            }
        }
    }
    return normal;
}

double circumradius(const Eigen::MatrixX3d& points, const Face& f) {
    const Eigen::Vector3d a = points.row(f[0]).transpose();
    const Eigen::Vector3d b = points.row(f[1]).transpose();
    const Eigen::Vector3d c = points.row(f[2]).transpose();
    const double twice_area = (b - a).cross(c - a).norm();
    return twice_area > 0 ? (a - b).norm() * (b - c).norm() * (c - a).norm() / (2 * twice_area)
                          : std::numeric_limits<double>::infinity();  // collinear: offered last
}

// The fans' triangles in the order they are offered to the mesh: held by more fans first (more
// tangent planes agree on them), then the smaller circumcircle first (the Delaunay choice
// where fans took different diagonals of a quadrilateral).
std::vector<Face> ranked_triangles(const std::map<Face, Vote>& votes,
                                   const Eigen::MatrixX3d& points) {
    std::vector<std::tuple<int, double, Face>> ranked;
    for (const auto& [key, vote] : votes) {
        ranked.emplace_back(-vote.count, circumradius(points, vote.face), vote.face);
    }
    std::sort(ranked.begin(), ranked.end());
    std::vector<Face> faces;
    for (const auto& [count, radius, face] : ranked) {
        faces.push_back(face);
    }
    return faces;
}

std::int64_t edge_key(Eigen::Index a, Eigen::Index b, Eigen::Index vertex_count) {
    return static_cast<std::int64_t>(std::min(a, b)) * vertex_count + std::max(a, b);
}

// The faces an edge has so far, by their corner opposite it.
struct EdgeFaces {
    int count = 0;
    std::array<Eigen::Index, 2> opposite = {-1, -1};
};

// The surface's normal across edge (a, b): its ends' normals (either side, made to agree),
// square to the edge; zero where they cancel.
Eigen::Vector3d normal_across(const std::vector<Neighbourhood>& hoods, Eigen::Index a,
                              Eigen::Index b, const Eigen::Vector3d& edge) {
    const Eigen::Vector3d at_a = hoods[static_cast<std::size_t>(a)].frame.col(2);
    const Eigen::Vector3d at_b = hoods[static_cast<std::size_t>(b)].frame.col(2);
    Eigen::Vector3d normal = at_a + (at_a.dot(at_b) < 0 ? -at_b : at_b);
    normal -= normal.dot(edge) * edge;
    return normal.squaredNorm() > 0 ? Eigen::Vector3d(normal.normalized())
                                    : Eigen::Vector3d::Zero();
}

// Whether corners c and d lie on the same side of edge (a, b), each measured square to the edge
// in the surface's tangent plane there: two faces that share the edge then fold onto each other
// (they overlap where two fans took the two diagonals of one quadrilateral). In the plane, so
// that noise along the normal does not make two faces that meet at a sharp bend look folded: a
// sliver's corner half a spacing off the plane turns the test in space and leaves cracks
// (docs/benchmarks.md, "Holes that touch the rim").
bool folds(const Eigen::MatrixX3d& points, const std::vector<Neighbourhood>& hoods, Eigen::Index a,
           Eigen::Index b, Eigen::Index c, Eigen::Index d) {
    const Eigen::Vector3d edge = (points.row(b) - points.row(a)).transpose().normalized();
    const Eigen::Vector3d normal = normal_across(hoods, a, b, edge);
    const auto across = [&](Eigen::Index x) {
        const Eigen::Vector3d offset = (points.row(x) - points.row(a)).transpose();
        const Eigen::Vector3d square = offset - offset.dot(edge) * edge;
        return Eigen::Vector3d(square - square.dot(normal) * normal);
    };
    return across(c).dot(across(d)) > 0;
}

// The ranked triangles, each kept only if none of its edges already has two faces or a face it
// would fold onto: the mesh is edge-manifold.
std::vector<Face> manifold_faces(const std::vector<Face>& ranked, const Eigen::MatrixX3d& points,
                                 const std::vector<Neighbourhood>& hoods) {
    std::unordered_map<std::int64_t, EdgeFaces> edge_faces;
    const auto fits = [&](const Face& f, int c) {
        const Eigen::Index a = f[static_cast<std::size_t>(c)];
        const Eigen::Index b = f[static_cast<std::size_t>((c + 1) % 3)];
        const EdgeFaces& at = edge_faces[edge_key(a, b, points.rows())];
        return at.count == 0 || (at.count == 1 && !folds(points, hoods, a, b, at.opposite[0],
                                                         f[static_cast<std::size_t>((c + 2) % 3)]));
    };
    std::vector<Face> faces;
    for (const Face& f : ranked) {
        if (fits(f, 0) && fits(f, 1) && fits(f, 2)) {
            for (int c = 0; c < 3; ++c) {
                EdgeFaces& at =
                    edge_faces[edge_key(f[static_cast<std::size_t>(c)],
                                        f[static_cast<std::size_t>((c + 1) % 3)], points.rows())];
                at.opposite[static_cast<std::size_t>(at.count++)] =
                    f[static_cast<std::size_t>((c + 2) % 3)];
            }
            faces.push_back(f);
        }
    }
    return faces;
}

bool has_directed_edge(const Face& f, Eigen::Index a, Eigen::Index b) {
    return (f[0] == a && f[1] == b) || (f[1] == a && f[2] == b) || (f[2] == a && f[0] == b);
}

// The faces' orientation made to agree across shared edges, and their components.
struct Orientation {
    std::vector<int> component;     // per face: the faces reached across shared edges
    std::vector<bool> contradicts;  // per face: it meets a better-ranked face the wrong way
    [[nodiscard]] bool consistent() const {
        return std::none_of(contradicts.begin(), contradicts.end(), [](bool c) { return c; });
    }
};

// Flips faces so that faces sharing an edge cross it in opposite directions, spreading from
// the better-ranked faces (`faces` is in rank order). Where the faces cannot agree (a Möbius
// band of faces bridging the two sides of a thin part), the lower-ranked face of the pair that
// meets the wrong way is marked.
Orientation orient_across_edges(std::vector<Face>& faces, Eigen::Index vertex_count) {
    std::unordered_map<std::int64_t, std::vector<std::size_t>> faces_at_edge;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        for (std::size_t c = 0; c < 3; ++c) {
            faces_at_edge[edge_key(faces[f][c], faces[f][(c + 1) % 3], vertex_count)].push_back(f);
        }
    }
    Orientation result{std::vector<int>(faces.size(), -1), std::vector<bool>(faces.size(), false)};
    int count = 0;
    for (std::size_t seed = 0; seed < faces.size(); ++seed) {
        if (result.component[seed] >= 0) {
            continue;
        }
        result.component[seed] = count;
        std::priority_queue<std::size_t, std::vector<std::size_t>, std::greater<>> frontier;
        frontier.push(seed);
        while (!frontier.empty()) {
            const std::size_t f = frontier.top();
            frontier.pop();
            for (std::size_t c = 0; c < 3; ++c) {
                const Eigen::Index a = faces[f][c];
                const Eigen::Index b = faces[f][(c + 1) % 3];
                for (const std::size_t g : faces_at_edge[edge_key(a, b, vertex_count)]) {
                    if (g == f) {
                        continue;
                    }
                    if (result.component[g] >= 0) {
                        if (has_directed_edge(faces[g], a, b)) {
                            result.contradicts[std::max(f, g)] = true;
                        }
                        continue;
                    }
                    if (has_directed_edge(faces[g], a, b)) {
                        std::swap(faces[g][1], faces[g][2]);
                    }
                    result.component[g] = count;
                    frontier.push(g);
                }
            }
        }
        ++count;
    }
    return result;
}

// `faces` oriented consistently, the faces that contradict the better-ranked ones left out
// until none does; returns each kept face's component.
std::vector<int> orientable_faces(std::vector<Face>& faces, Eigen::Index vertex_count) {
    Orientation orientation = orient_across_edges(faces, vertex_count);
    while (!orientation.consistent()) {
        std::vector<Face> kept;
        for (std::size_t f = 0; f < faces.size(); ++f) {
            if (!orientation.contradicts[f]) {
                kept.push_back(faces[f]);
            }
        }
        faces = std::move(kept);
        orientation = orient_across_edges(faces, vertex_count);
    }
    return orientation.component;
}

std::vector<Eigen::Vector3d> given_normals(const Eigen::MatrixX3d& normals) {
    std::vector<Eigen::Vector3d> result;
    for (Eigen::Index i = 0; i < normals.rows(); ++i) {
        result.emplace_back(normals.row(i).transpose().normalized());
    }
    return result;
}

void flip(Face& face) {
    std::swap(face[1], face[2]);
}

// Turns each component to agree with the oriented normals of its corners (area-weighted),
// then all faces so that they enclose a positive volume about the points' centroid (outward,
// where the surface is closed or nearly so).
void orient_outward(std::vector<Face>& faces, const std::vector<int>& component,
                    const Eigen::MatrixX3d& points, const std::vector<Eigen::Vector3d>& normal) {
    const int count =
        component.empty() ? 0 : *std::max_element(component.begin(), component.end()) + 1;
    std::vector<double> agreement(static_cast<std::size_t>(count), 0);
    const auto corner = [&](const Face& f, std::size_t c) {
        return Eigen::Vector3d(points.row(f[c]).transpose());
    };
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const Face& face = faces[f];
        const Eigen::Vector3d area_normal =
            (corner(face, 1) - corner(face, 0)).cross(corner(face, 2) - corner(face, 0));
        for (const Eigen::Index v : face) {
            agreement[static_cast<std::size_t>(component[f])] +=
                area_normal.dot(normal[static_cast<std::size_t>(v)]);
        }
    }
    const Eigen::Vector3d centroid = points.colwise().mean().transpose();
    double volume = 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        if (agreement[static_cast<std::size_t>(component[f])] < 0) {
            flip(faces[f]);
        }
        const Face& face = faces[f];
        volume += (corner(face, 0) - centroid)
                      .dot((corner(face, 1) - centroid).cross(corner(face, 2) - centroid));
    }
    if (volume < 0) {
        std::for_each(faces.begin(), faces.end(), flip);
    }
}

// Sorted corners of a face, to find a face however it is turned.
Face sorted(Face face) {
    std::sort(face.begin(), face.end());
    return face;
}

// The faces that close a gap of three or four boundary edges (`loop` as the faces run them,
// so the new faces run it the other way), or none where they would repeat a face or an edge: a
// four-edge gap is split along its shorter diagonal, or along the other where that one is an
// edge already.
std::vector<Face> closing_faces(const std::vector<int>& loop, const Eigen::MatrixX3d& points,
                                const std::set<Face>& existing,
                                const std::set<std::pair<int, int>>& edges) {
    std::vector<std::vector<Face>> candidates;
    if (loop.size() == 3) {
        candidates.push_back({{loop[0], loop[2], loop[1]}});
    } else {
        const auto split = [&](std::size_t s) -> std::vector<Face> {
            const int a = loop[s];
            const int b = loop[s + 1];
            const int c = loop[s + 2];
            const int d = loop[(s + 3) % 4];
            if (edges.contains(std::minmax(a, c))) {
                return {};
            }
            return {{a, d, c}, {a, c, b}};
        };
        const auto length = [&](int a, int b) { return (points.row(a) - points.row(b)).norm(); };
        const std::size_t shorter = length(loop[0], loop[2]) <= length(loop[1], loop[3]) ? 0 : 1;
        candidates.push_back(split(shorter));
        candidates.push_back(split(1 - shorter));
    }
    for (const std::vector<Face>& closing : candidates) {
        if (!closing.empty() && std::none_of(closing.begin(), closing.end(), [&](const Face& f) {
                return existing.contains(sorted(f));
            })) {
            return closing;
        }
    }
    return {};
}

// Closes the gaps of three or four edges there are now; whether it closed any.
bool close_small_gaps_once(TriangleMesh& mesh) {
    std::set<Face> existing;
    std::set<std::pair<int, int>> edges;
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        existing.insert(sorted({mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)}));
        for (int k = 0; k < 3; ++k) {
            edges.insert(std::minmax(mesh.F(f, k), mesh.F(f, (k + 1) % 3)));
        }
    }
    std::vector<Face> added;
    for (const std::vector<int>& loop : boundary_loops(mesh)) {
        if (loop.size() == 3 || loop.size() == 4) {
            for (const Face& face : closing_faces(loop, mesh.V, existing, edges)) {
                existing.insert(sorted(face));
                for (int k = 0; k < 3; ++k) {
                    edges.insert(std::minmax(static_cast<int>(face[static_cast<std::size_t>(k)]),
                                             static_cast<int>(face[(k + 1) % 3])));
                }
                added.push_back(face);
            }
        }
    }
    const Eigen::Index kept = mesh.F.rows();
    mesh.F.conservativeResize(kept + static_cast<Eigen::Index>(added.size()), 3);
    for (std::size_t f = 0; f < added.size(); ++f) {
        for (int c = 0; c < 3; ++c) {
            mesh.F(kept + static_cast<Eigen::Index>(f), c) = static_cast<int>(added[f][c]);
        }
    }
    return !added.empty();
}

// A gap of three or four boundary edges is a face the fans did not agree on (each point's
// Delaunay choice among its own neighbours differs across a near-square quadrilateral), not a
// hole the sampling can show: it is closed, so that hole_area() and the spectrum see the
// surface the points sample. Closing some can leave others where loops met at a vertex, so
// until none is left (each pass takes boundary edges away and adds none).
void close_small_gaps(TriangleMesh& mesh) {
    while (close_small_gaps_once(mesh)) {
    }
}

void check_points(const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& normals,
                  const PointCloudSurfaceOptions& options) {
    if (points.rows() < 4) {
        throw InvalidInput("point_cloud_surface: " + std::to_string(points.rows()) +
                           " points; at least 4 are needed");
    }
    if (!detail::all_finite(points)) {
        throw InvalidInput("point_cloud_surface: a point has a non-finite coordinate");
    }
    if (points.cwiseAbs().maxCoeff() > kLargestCoordinate) {
        throw InvalidInput("point_cloud_surface: a point has a coordinate beyond ±1e50");
    }
    if (options.neighbours < 4) {
        throw InvalidInput("point_cloud_surface: neighbours must be at least 4");
    }
    if (normals.rows() > 0 && normals.rows() != points.rows()) {
        throw InvalidInput("point_cloud_surface: " + std::to_string(normals.rows()) +
                           " normals for " + std::to_string(points.rows()) + " points");
    }
    for (Eigen::Index i = 0; i < normals.rows(); ++i) {
        if (!detail::all_finite(Eigen::Vector3d(normals.row(i).transpose())) ||
            normals.row(i).squaredNorm() == 0) {
            throw InvalidInput("point_cloud_surface: normal " + std::to_string(i) +
                               " is zero or not finite");
        }
    }
}

}  // namespace

TriangleMesh point_cloud_surface(const Eigen::MatrixX3d& points,
                                 const PointCloudSurfaceOptions& options) {
    return point_cloud_surface(points, Eigen::MatrixX3d(0, 3), options);
}

TriangleMesh point_cloud_surface(const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& normals,
                                 const PointCloudSurfaceOptions& options) {
    check_points(points, normals, options);
    const std::vector<Neighbourhood> hoods =
        neighbourhoods(points, normals, first_copies(points), options.neighbours);
    std::vector<Face> faces =
        manifold_faces(ranked_triangles(votes_of_fans(points, hoods), points), points, hoods);
    if (faces.empty()) {
        throw InvalidInput(
            "point_cloud_surface: no face could be built (the points lie on a line, or are too "
            "far apart for their neighbours to agree)");
    }
    const std::vector<int> component = orientable_faces(faces, points.rows());
    orient_outward(faces, component, points,
                   normals.rows() > 0 ? given_normals(normals) : oriented_normals(hoods));
    TriangleMesh mesh{points, Eigen::MatrixX3i(static_cast<Eigen::Index>(faces.size()), 3)};
    for (std::size_t f = 0; f < faces.size(); ++f) {
        for (int c = 0; c < 3; ++c) {
            mesh.F(static_cast<Eigen::Index>(f), c) = static_cast<int>(faces[f][c]);
        }
    }
    close_small_gaps(mesh);
    return mesh;
}

}  // namespace genflow
