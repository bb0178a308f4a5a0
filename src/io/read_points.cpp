// SPDX-License-Identifier: MIT
#include "genflow/io/read_points.h"

#include <cmath>
#include <string_view>

#include "genflow/exceptions.h"
#include "genflow/io/read_file.h"
#include "genflow/io/read_mesh.h"
#include "io/parse_context.h"
#include "io/readers.h"

namespace genflow {

namespace {

// Rows of `rows` as a #rows×3 matrix.
Eigen::MatrixX3d matrix_of(const std::vector<Eigen::Vector3d>& rows) {
    Eigen::MatrixX3d result(static_cast<Eigen::Index>(rows.size()), 3);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        result.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
    }
    return result;
}

PointCloud parse_xyz(const std::filesystem::path& path) {
    const std::string text = read_file(path);
    detail::TextScanner scanner(text);
    std::vector<std::string_view> tokens;
    std::vector<Eigen::Vector3d> points;
    std::vector<Eigen::Vector3d> normals;
    bool with_normals = false;  // as the first point's line says
    for (std::size_t line = 1; !scanner.at_end(); ++line) {
        const std::string_view content = scanner.next_line();
        detail::split_tokens(content.substr(0, content.find('#')), tokens);
        if (tokens.empty()) {
            continue;
        }
        const auto fail = [&](const std::string& problem) {
            throw IoError(path.string() + ": line " + std::to_string(line) + ": " + problem);
        };
        if (points.empty()) {
            with_normals = tokens.size() >= 6;
        }
        if (tokens.size() < (with_normals ? 6U : 3U)) {
            fail(with_normals ? "expected 'x y z nx ny nz', as on the first point's line"
                              : "expected 'x y z' (optionally followed by a normal)");
        }
        const auto vector_at = [&](std::size_t first) {
            Eigen::Vector3d v;
            for (int c = 0; c < 3; ++c) {
                const std::string_view token = tokens[first + static_cast<std::size_t>(c)];
                if (!detail::parse_double(token, v[c]) || !std::isfinite(v[c])) {
                    fail("expected a finite number, got '" + std::string(token) + "'");
                }
            }
            return v;
        };
        points.push_back(vector_at(0));
        if (with_normals) {
            normals.push_back(vector_at(3));
            if (normals.back().squaredNorm() == 0) {
                fail("the normal is zero");
            }
        }
    }
    return {matrix_of(points), matrix_of(normals)};
}

// A PLY file's vertices and, where the vertex element has them, their normals.
PointCloud parse_ply_points(const std::filesystem::path& path, std::vector<std::string>* warnings) {
    const std::string name = path.string();
    PointCloud cloud;
    VertexAttributes attributes;
    cloud.points = detail::parse_ply(detail::read_mesh_file(path), {name, warnings}, &attributes).V;
    cloud.normals = std::move(attributes.normals);
    for (Eigen::Index i = 0; i < cloud.normals.rows(); ++i) {
        if (!cloud.normals.row(i).allFinite() || cloud.normals.row(i).squaredNorm() == 0) {
            throw IoError(name + ": point " + std::to_string(i) + ": the normal is " +
                          (cloud.normals.row(i).allFinite() ? "zero" : "not finite"));
        }
    }
    return cloud;
}

}  // namespace

bool is_xyz_file(const std::filesystem::path& path) {
    return detail::iequals(path.extension().string(), ".xyz");
}

PointCloud read_points(const std::filesystem::path& path, std::vector<std::string>* warnings) {
    PointCloud cloud;
    if (is_xyz_file(path)) {
        cloud = parse_xyz(path);
    } else if (mesh_format_from_extension(path) == MeshFormat::Ply) {
        cloud = parse_ply_points(path, warnings);
    } else {
        cloud.points = read_mesh(path, warnings).V;
    }
    if (cloud.points.rows() == 0) {
        throw IoError(path.string() + ": no point");
    }
    for (Eigen::Index i = 0; i < cloud.points.rows(); ++i) {
        if (!std::isfinite(cloud.points(i, 0)) || !std::isfinite(cloud.points(i, 1)) ||
            !std::isfinite(cloud.points(i, 2))) {
            throw IoError(path.string() + ": point " + std::to_string(i) +
                          " has a non-finite coordinate");
        }
    }
    return cloud;
}

}  // namespace genflow
