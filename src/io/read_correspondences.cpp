// SPDX-License-Identifier: MIT
#include "genflow/io/read_correspondences.h"

#include <cmath>
#include <string>

#include "genflow/exceptions.h"
#include "io/parse_context.h"

namespace genflow {

namespace {

// The tolerance of the barycentric coordinates: write_correspondences() prints 9 digits.
constexpr double kBarycentricSlack = 1e-6;

// The problem with a line's numbers, or nothing.
std::string problem_with(const SurfacePoint& p, Eigen::Index faces) {
    if (p.face < 0 || p.face >= faces) {
        return "face " + std::to_string(p.face) + " outside 0.." + std::to_string(faces - 1);
    }
    const Eigen::Vector3d& b = p.barycentric;
    // std::isfinite, not allFinite(): that computes x − x, which traps on an infinity.
    if (!std::isfinite(b[0]) || !std::isfinite(b[1]) || !std::isfinite(b[2]) ||
        b.minCoeff() < -kBarycentricSlack || std::abs(b.sum() - 1) > kBarycentricSlack) {
        return "barycentric coordinates must be at least 0 and sum to 1";
    }
    if (!std::isfinite(p.distance) || p.distance < 0) {
        return "the distance must be a finite number at least 0";
    }
    return "";
}

}  // namespace

std::vector<SurfacePoint> read_correspondences(const std::filesystem::path& path,
                                               const TriangleMesh& target,
                                               Eigen::Index template_vertices) {
    std::vector<SurfacePoint> points;
    detail::for_each_data_line(path, [&](const detail::DataLine& line) {
        const std::vector<std::string_view>& tokens = line.tokens;
        SurfacePoint p;
        std::int64_t face = 0;
        if (tokens.size() != 5 || !detail::parse_integer(tokens[0], face) ||
            !detail::parse_double(tokens[1], p.barycentric[0]) ||
            !detail::parse_double(tokens[2], p.barycentric[1]) ||
            !detail::parse_double(tokens[3], p.barycentric[2]) ||
            !detail::parse_double(tokens[4], p.distance)) {
            line.fail("expected 'face b0 b1 b2 distance'");
        }
        p.face = static_cast<Eigen::Index>(face);
        if (const std::string problem = problem_with(p, target.F.rows()); !problem.empty()) {
            line.fail(problem);
        }
        if (static_cast<Eigen::Index>(points.size()) == template_vertices) {
            line.fail("more lines than the template's " + std::to_string(template_vertices) +
                      " vertices");
        }
        p.point = Eigen::Vector3d::Zero();
        for (int c = 0; c < 3; ++c) {
            p.point += p.barycentric[c] * target.V.row(target.F(p.face, c)).transpose();
        }
        points.push_back(p);
    });
    if (static_cast<Eigen::Index>(points.size()) != template_vertices) {
        throw IoError(path.string() + ": " + std::to_string(points.size()) +
                      " correspondences for the template's " + std::to_string(template_vertices) +
                      " vertices");
    }
    return points;
}

}  // namespace genflow
