// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace genflow {

/// #V×3 vertex colours, sRGB 0–255, a row per vertex.
using VertexColors = Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Per-vertex values that travel with a mesh into its file, beside positions and faces.
struct VertexAttributes {
    /// A colour per vertex, or no rows.
    VertexColors colors;
    /// A normal per vertex as the file gives it (not necessarily of unit length), or no rows.
    Eigen::MatrixX3d normals;
    /// Named values per vertex (a PLY property each, e.g. "distance"), each as long as V.
    std::vector<std::pair<std::string, Eigen::VectorXd>> scalars;
};

}  // namespace genflow
