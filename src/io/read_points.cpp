// SPDX-License-Identifier: MIT
#include "genflow/io/read_points.h"

#include <cmath>
#include <string_view>

#include "genflow/exceptions.h"
#include "genflow/io/read_mesh.h"
#include "io/parse_context.h"

namespace genflow {

namespace {

Eigen::MatrixX3d parse_xyz(const std::filesystem::path& path) {
    const std::string text = detail::read_text(path);
    detail::TextScanner scanner(text);
    std::vector<std::string_view> tokens;
    std::vector<Eigen::Vector3d> points;
    for (std::size_t line = 1; !scanner.at_end(); ++line) {
        const std::string_view content = scanner.next_line();
        detail::split_tokens(content.substr(0, content.find('#')), tokens);
        if (tokens.empty()) {
            continue;
        }
        const auto fail = [&](const std::string& problem) {
            throw IoError(path.string() + ": line " + std::to_string(line) + ": " + problem);
        };
        if (tokens.size() < 3) {
            fail("expected 'x y z' (optionally followed by a normal)");
        }
        Eigen::Vector3d point;
        for (int c = 0; c < 3; ++c) {
            const std::string_view token = tokens[static_cast<std::size_t>(c)];
            if (!detail::parse_double(token, point[c]) || !std::isfinite(point[c])) {
                fail("expected a finite coordinate, got '" + std::string(token) + "'");
            }
        }
        points.push_back(point);
    }
    Eigen::MatrixX3d result(static_cast<Eigen::Index>(points.size()), 3);
    for (std::size_t i = 0; i < points.size(); ++i) {
        result.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
    }
    return result;
}

}  // namespace

bool is_xyz_file(const std::filesystem::path& path) {
    return detail::iequals(path.extension().string(), ".xyz");
}

Eigen::MatrixX3d read_points(const std::filesystem::path& path,
                             std::vector<std::string>* warnings) {
    Eigen::MatrixX3d points = is_xyz_file(path) ? parse_xyz(path) : read_mesh(path, warnings).V;
    if (points.rows() == 0) {
        throw IoError(path.string() + ": no point");
    }
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
        if (!std::isfinite(points(i, 0)) || !std::isfinite(points(i, 1)) ||
            !std::isfinite(points(i, 2))) {
            throw IoError(path.string() + ": point " + std::to_string(i) +
                          " has a non-finite coordinate");
        }
    }
    return points;
}

}  // namespace genflow
