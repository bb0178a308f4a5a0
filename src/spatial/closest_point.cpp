// SPDX-License-Identifier: MIT
#include "genflow/spatial/closest_point.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "genflow/exceptions.h"
#include "operators/triangle.h"

namespace genflow {

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    // Voronoi regions of the vertices, then of the edges, then the face.
    const Eigen::Vector3d ab = b - a;
    const Eigen::Vector3d ac = c - a;
    const Eigen::Vector3d ap = p - a;
    const double d1 = ab.dot(ap);
    const double d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) {
        return {1, 0, 0};
    }
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp);
    const double d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) {
        return {0, 1, 0};
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) {
        const double v = d1 / (d1 - d3);
        return {1 - v, v, 0};
    }
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp);
    const double d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) {
        return {0, 0, 1};
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) {
        const double w = d2 / (d2 - d6);
        return {1 - w, 0, w};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0 && (d4 - d3) + (d5 - d6) > 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - w, w};
    }
    const double denominator = va + vb + vc;
    if (!(denominator > 0)) {
        // Degenerate (collinear or coincident corners) and p projects inside: the nearest of
        // the three edges decides.
        const auto on_segment = [&](const Eigen::Vector3d& s, const Eigen::Vector3d& t) {
            const Eigen::Vector3d st = t - s;
            const double length2 = st.squaredNorm();
            return length2 > 0 ? std::clamp((p - s).dot(st) / length2, 0.0, 1.0) : 0.0;
        };
        const double t_ab = on_segment(a, b);
        const double t_bc = on_segment(b, c);
        const double t_ca = on_segment(c, a);
        const Eigen::Vector3d candidates[3] = {
            {1 - t_ab, t_ab, 0}, {0, 1 - t_bc, t_bc}, {t_ca, 0, 1 - t_ca}};
        int best = 0;
        double best_distance = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d q =
                candidates[k][0] * a + candidates[k][1] * b + candidates[k][2] * c;
            if ((p - q).squaredNorm() < best_distance) {
                best_distance = (p - q).squaredNorm();
                best = k;
            }
        }
        return candidates[best];
    }
    const double v = vb / denominator;
    const double w = vc / denominator;
    return {1 - v - w, v, w};
}

namespace {

struct Box {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

    void extend(const Eigen::Vector3d& p) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    void extend(const Box& other) {
        lo = lo.cwiseMin(other.lo);
        hi = hi.cwiseMax(other.hi);
    }
    [[nodiscard]] double squared_distance(const Eigen::Vector3d& p) const {
        return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
    }
};

struct Node {
    Box box;
    int first = 0;   // leaf: start of its range in `order`; inner node: the left child
    int count = 0;   // leaf: number of faces; 0 for inner nodes
    int right = -1;  // inner node: the right child
};

constexpr int kLeafSize = 4;

}  // namespace

// The depth-first stack holds at most one pending sibling per level plus the node in hand; a
// median split halves the faces per level, so 64 levels cover any addressable mesh.
constexpr int kMaxStack = 64;

struct TriangleBvh::Impl {
    TriangleMesh mesh;
    std::vector<Eigen::Vector3d> corners;  // 3 per face, in leaf order: a leaf reads one run
    std::vector<Box> face_boxes;
    std::vector<Eigen::Vector3d> centroids;
    std::vector<int> order;
    std::vector<Node> nodes;

    int build(int first, int count) {
        Node node;
        for (int k = first; k < first + count; ++k) {
            node.box.extend(
                face_boxes[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])]);
        }
        const int index = static_cast<int>(nodes.size());
        nodes.push_back(node);
        if (count <= kLeafSize) {
            nodes[static_cast<std::size_t>(index)].first = first;
            nodes[static_cast<std::size_t>(index)].count = count;
            return index;
        }
        Box centroid_box;
        for (int k = first; k < first + count; ++k) {
            centroid_box.extend(
                centroids[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])]);
        }
        int axis = 0;
        (centroid_box.hi - centroid_box.lo).maxCoeff(&axis);
        const int middle = first + count / 2;
        std::nth_element(order.begin() + first, order.begin() + middle,
                         order.begin() + first + count, [&](int x, int y) {
                             return centroids[static_cast<std::size_t>(x)][axis] <
                                    centroids[static_cast<std::size_t>(y)][axis];
                         });
        const int left = build(first, middle - first);
        const int right = build(middle, first + count - middle);
        nodes[static_cast<std::size_t>(index)].first = left;
        nodes[static_cast<std::size_t>(index)].right = right;
        return index;
    }
};

Eigen::MatrixX3d positions_of(const std::vector<SurfacePoint>& points) {
    Eigen::MatrixX3d positions(static_cast<Eigen::Index>(points.size()), 3);
    for (Eigen::Index i = 0; i < positions.rows(); ++i) {
        positions.row(i) = points[static_cast<std::size_t>(i)].point.transpose();
    }
    return positions;
}

TriangleBvh::TriangleBvh(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
    detail::require_valid_mesh(mesh, "TriangleBvh");
    if (mesh.F.rows() == 0) {
        throw InvalidInput("TriangleBvh: mesh has no faces");
    }
    auto& d = *impl_;
    d.mesh = mesh;
    const auto m = static_cast<std::size_t>(mesh.F.rows());
    d.face_boxes.resize(m);
    d.centroids.resize(m);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d corner = mesh.V.row(mesh.F(f, k)).transpose();
            d.face_boxes[static_cast<std::size_t>(f)].extend(corner);
            centroid += corner / 3;
        }
        d.centroids[static_cast<std::size_t>(f)] = centroid;
    }
    d.order.resize(m);
    std::iota(d.order.begin(), d.order.end(), 0);
    d.nodes.reserve(2 * m / kLeafSize + 2);
    d.build(0, static_cast<int>(m));
    d.corners.resize(3 * m);
    for (std::size_t k = 0; k < m; ++k) {
        for (int j = 0; j < 3; ++j) {
            d.corners[3 * k + static_cast<std::size_t>(j)] =
                mesh.V.row(mesh.F(d.order[k], j)).transpose();
        }
    }
}

TriangleBvh::~TriangleBvh() = default;
TriangleBvh::TriangleBvh(TriangleBvh&&) noexcept = default;
TriangleBvh& TriangleBvh::operator=(TriangleBvh&&) noexcept = default;

// Depth-first, nearer child first, every box no nearer than the best face so far pruned.
SurfacePoint TriangleBvh::closest_point(const Eigen::Vector3d& query) const {
    const auto& d = *impl_;
    SurfacePoint best;
    double best2 = std::numeric_limits<double>::infinity();
    // Each pending node with its box's squared distance, computed once when it is pushed.
    std::array<std::pair<int, double>, kMaxStack> stack{};
    int top = 0;
    stack[top++] = {0, d.nodes[0].box.squared_distance(query)};
    while (top > 0) {
        const auto [index, box2] = stack[--top];
        if (box2 >= best2) {
            continue;
        }
        const Node& node = d.nodes[static_cast<std::size_t>(index)];
        if (node.count > 0) {
            for (int k = node.first; k < node.first + node.count; ++k) {
                const Eigen::Vector3d* corner = &d.corners[3 * static_cast<std::size_t>(k)];
                const Eigen::Vector3d w =
                    closest_point_on_triangle(query, corner[0], corner[1], corner[2]);
                const Eigen::Vector3d point =
                    w[0] * corner[0] + w[1] * corner[1] + w[2] * corner[2];
                const double distance2 = (point - query).squaredNorm();
                if (distance2 < best2) {
                    best2 = distance2;
                    best.face = d.order[static_cast<std::size_t>(k)];
                    best.barycentric = w;
                    best.point = point;
                }
            }
            continue;
        }
        const double left =
            d.nodes[static_cast<std::size_t>(node.first)].box.squared_distance(query);
        const double right =
            d.nodes[static_cast<std::size_t>(node.right)].box.squared_distance(query);
        // Push the farther child first so the nearer one is explored first; a child no nearer
        // than the best face is not pushed at all.
        const std::pair<int, double> near_child =
            left < right ? std::pair{node.first, left} : std::pair{node.right, right};
        const std::pair<int, double> far_child =
            left < right ? std::pair{node.right, right} : std::pair{node.first, left};
        if (far_child.second < best2) {
            stack[top++] = far_child;
        }
        if (near_child.second < best2) {
            stack[top++] = near_child;
        }
    }
    best.distance = std::sqrt(best2);
    return best;
}

}  // namespace genflow
