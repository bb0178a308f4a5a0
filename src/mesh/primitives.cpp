// SPDX-License-Identifier: MIT
#include "genflow/mesh/primitives.h"

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

}  // namespace genflow
