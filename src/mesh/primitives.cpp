// SPDX-License-Identifier: MIT
#include "genflow/mesh/primitives.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "genflow/exceptions.h"
#include "operators/triangle.h"

namespace genflow {

TriangleMesh make_icosphere(int level, double radius) {
    if (level < 0 || level > 9) {
        throw InvalidInput("make_icosphere: level must lie in [0, 9], got " +
                           std::to_string(level));
    }
    if (!detail::finite_above(radius, 0)) {
        throw InvalidInput("make_icosphere: radius must be positive and finite");
    }
    const double t = std::numbers::phi;
    std::vector<Eigen::Vector3d> vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                             {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                             {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<Eigen::Vector3i> faces = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (auto& v : vertices) {
        v.normalize();
    }
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<int, int>, int> midpoint;
        const auto middle = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            const auto [it, inserted] =
                midpoint.try_emplace(key, static_cast<int>(vertices.size()));
            if (inserted) {
                vertices.push_back(
                    (vertices[static_cast<std::size_t>(a)] + vertices[static_cast<std::size_t>(b)])
                        .normalized());
            }
            return it->second;
        };
        std::vector<Eigen::Vector3i> finer;
        finer.reserve(4 * faces.size());
        for (const auto& f : faces) {
            const int ab = middle(f[0], f[1]);
            const int bc = middle(f[1], f[2]);
            const int ca = middle(f[2], f[0]);
            finer.emplace_back(f[0], ab, ca);
            finer.emplace_back(f[1], bc, ab);
            finer.emplace_back(f[2], ca, bc);
            finer.emplace_back(ab, bc, ca);
        }
        faces = std::move(finer);
    }
    TriangleMesh mesh;
    mesh.V.resize(static_cast<Eigen::Index>(vertices.size()), 3);
    mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        mesh.V.row(static_cast<Eigen::Index>(i)) = radius * vertices[i].transpose();
    }
    for (std::size_t f = 0; f < faces.size(); ++f) {
        mesh.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
    }
    return mesh;
}

TriangleMesh make_torus(int rings, int sides, double major_radius, double minor_radius) {
    if (rings < 3 || sides < 3) {
        throw InvalidInput("make_torus: rings and sides must be at least 3");
    }
    if (!detail::finite_above(minor_radius, 0) ||
        !detail::finite_above(major_radius, minor_radius)) {
        throw InvalidInput("make_torus: need 0 < minor_radius < major_radius < inf");
    }
    TriangleMesh mesh;
    mesh.V.resize(static_cast<Eigen::Index>(rings) * sides, 3);
    mesh.F.resize(2 * static_cast<Eigen::Index>(rings) * sides, 3);
    const auto index = [&](int r, int s) { return (r % rings) * sides + (s % sides); };
    for (int r = 0; r < rings; ++r) {
        const double u = 2 * std::numbers::pi * r / rings;
        for (int s = 0; s < sides; ++s) {
            const double v = 2 * std::numbers::pi * s / sides;
            const double w = major_radius + minor_radius * std::cos(v);
            mesh.V.row(index(r, s)) << w * std::cos(u), w * std::sin(u), minor_radius * std::sin(v);
        }
    }
    Eigen::Index f = 0;
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < sides; ++s) {
            // Counter-clockwise seen from outside: ring direction × tube direction = outward.
            mesh.F.row(f++) << index(r, s), index(r + 1, s), index(r + 1, s + 1);
            mesh.F.row(f++) << index(r, s), index(r + 1, s + 1), index(r, s + 1);
        }
    }
    return mesh;
}

TriangleMesh make_grid(int cells, double size) {
    if (cells < 1 || !detail::finite_above(size, 0)) {
        throw InvalidInput("make_grid: need cells >= 1 and a positive finite size");
    }
    const int n = cells + 1;
    TriangleMesh mesh;
    mesh.V.resize(static_cast<Eigen::Index>(n) * n, 3);
    mesh.F.resize(2 * static_cast<Eigen::Index>(cells) * cells, 3);
    for (int r = 0; r < n; ++r) {
        for (int c = 0; c < n; ++c) {
            mesh.V.row(r * n + c) << size * c / cells, size * r / cells, 0.0;
        }
    }
    Eigen::Index f = 0;
    for (int r = 0; r < cells; ++r) {
        for (int c = 0; c < cells; ++c) {
            const int a = r * n + c;
            mesh.F.row(f++) << a, a + 1, a + n + 1;
            mesh.F.row(f++) << a, a + n + 1, a + n;
        }
    }
    return mesh;
}

TriangleMesh add_noise(TriangleMesh mesh, double sigma, std::uint64_t seed) {
    if (!detail::finite_at_least(sigma, 0)) {
        throw InvalidInput("add_noise: sigma must be non-negative and finite");
    }
    std::mt19937_64 generator(seed);
    std::normal_distribution<double> normal(0.0, sigma);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            mesh.V(i, c) += normal(generator);
        }
    }
    return mesh;
}

TriangleMesh make_ellipsoid(int level, const Eigen::Vector3d& radii, std::uint64_t sampling_seed) {
    if (!detail::finite_above(radii.x(), 0) || !detail::finite_above(radii.y(), 0) ||
        !detail::finite_above(radii.z(), 0)) {
        throw InvalidInput("make_ellipsoid: radii must be positive and finite");
    }
    TriangleMesh mesh = make_icosphere(level);
    if (sampling_seed != 0) {
        std::mt19937_64 generator(sampling_seed);
        std::normal_distribution<double> normal(0.0, 1.0);
        Eigen::Quaterniond q(normal(generator), normal(generator), normal(generator),
                             normal(generator));
        q.normalize();
        mesh.V = mesh.V * q.toRotationMatrix().transpose();
    }
    mesh.V = mesh.V * radii.asDiagonal();
    return mesh;
}

TriangleMesh make_limb(int level, std::uint64_t sampling_seed) {
    TriangleMesh mesh = make_ellipsoid(level, {3, 0.55, 0.45}, sampling_seed);
    const Eigen::Vector3d hump = Eigen::Vector3d(0.75, 0.66, 0).normalized();
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        // A hump on top of the +x end, found through the direction on the unit sphere.
        const Eigen::Vector3d n =
            mesh.V.row(i).transpose().cwiseQuotient(Eigen::Vector3d(3, 0.55, 0.45));
        mesh.V.row(i) *= 1 + 0.5 * std::exp((n.normalized().dot(hump) - 1) / 0.03);
        const double u = std::clamp(mesh.V(i, 0) / 3, -1.0, 1.0);  // along the shape
        mesh.V(i, 1) = mesh.V(i, 1) * (1 + 0.3 * u) - 0.25 * u * u;
        mesh.V(i, 2) = mesh.V(i, 2) * (1 + 0.2 * u);
    }
    return mesh;
}

Eigen::MatrixX3d bend_at_joints(const Eigen::MatrixX3d& points, const std::vector<Joint>& joints) {
    Eigen::MatrixX3d posed = points;
    for (const Joint& joint : joints) {
        const bool finite = joint.centre.allFinite() && joint.direction.allFinite() &&
                            joint.axis.allFinite() && std::isfinite(joint.angle);
        if (!finite || !(joint.direction.norm() > 0) || !(joint.axis.norm() > 0) ||
            !detail::finite_above(joint.width, 0)) {
            throw InvalidInput(
                "bend_at_joints: a joint needs finite values, a non-zero direction and axis and "
                "a positive width");
        }
        const Eigen::Vector3d direction = joint.direction.normalized();
        const Eigen::Vector3d axis = joint.axis.normalized();
        for (Eigen::Index i = 0; i < points.rows(); ++i) {
            const Eigen::Vector3d rest = points.row(i).transpose();
            const double t =
                std::clamp(0.5 + 0.5 * direction.dot(rest - joint.centre) / joint.width, 0.0, 1.0);
            const double blend = t * t * (3 - 2 * t);
            if (blend == 0) {
                continue;
            }
            const Eigen::AngleAxisd turn(blend * joint.angle, axis);
            posed.row(i) =
                (joint.centre + turn * (posed.row(i).transpose() - joint.centre)).transpose();
        }
    }
    return posed;
}

}  // namespace genflow
