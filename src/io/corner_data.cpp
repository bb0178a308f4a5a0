// SPDX-License-Identifier: MIT
#include "io/corner_data.h"

#include <algorithm>
#include <utility>

namespace genflow::detail {

void append_fan(const std::vector<std::int64_t>& polygon, std::vector<int>& triangles) {
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
        triangles.push_back(static_cast<int>(polygon[0]));
        triangles.push_back(static_cast<int>(polygon[k]));
        triangles.push_back(static_cast<int>(polygon[k + 1]));
    }
}

std::optional<Eigen::MatrixXd> per_vertex_rows(const Eigen::MatrixX3i& faces,
                                               const Eigen::MatrixXd& table,
                                               const Eigen::MatrixX3i& corner_rows,
                                               Eigen::Index vertex_count) {
    Eigen::MatrixXd rows(vertex_count, table.cols());
    std::vector<bool> seen(static_cast<std::size_t>(vertex_count), false);
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            const Eigen::Index v = faces(f, c);
            if (v < 0 || v >= vertex_count) {
                return std::nullopt;  // validate() names such a face
            }
            const auto row = table.row(corner_rows(f, c));
            if (seen[static_cast<std::size_t>(v)] && rows.row(v) != row) {
                return std::nullopt;
            }
            rows.row(v) = row;
            seen[static_cast<std::size_t>(v)] = true;
        }
    }
    if (std::find(seen.begin(), seen.end(), false) != seen.end()) {
        return std::nullopt;
    }
    return rows;
}

Eigen::MatrixX3i as_faces(const std::vector<int>& triangles) {
    return Eigen::Map<const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(
        triangles.data(), static_cast<Eigen::Index>(triangles.size() / 3), 3);
}

void store_texture_coordinates(std::optional<Eigen::MatrixXd> per_vertex, Eigen::MatrixXd table,
                               Eigen::MatrixX3i corner_rows, VertexAttributes& attributes) {
    if (per_vertex) {
        attributes.uvs = std::move(*per_vertex);
    } else {
        attributes.corner_uvs = std::move(table);
        attributes.corner_uv_faces = std::move(corner_rows);
    }
}

}  // namespace genflow::detail
