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

/// What travels with a mesh into its file beside positions and faces: values per vertex, and
/// texture coordinates per vertex or per face corner.
struct VertexAttributes {
    /// A colour per vertex, or no rows.
    VertexColors colors;
    /// A normal per vertex as the file gives it (not necessarily of unit length), or no rows.
    Eigen::MatrixX3d normals;
    /// Named values per vertex (a PLY property each, e.g. "distance"), each as long as V.
    std::vector<std::pair<std::string, Eigen::VectorXd>> scalars;
    /// Texture coordinates (u, v) per vertex, v upwards as in OBJ and PLY, or no rows.
    Eigen::MatrixX2d uvs;
    /// Texture coordinates per face corner, where a seam gives a vertex several (an OBJ file's
    /// `f v/t`, a PLY face's `texcoord` list): a table of (u, v) rows ...
    Eigen::MatrixX2d corner_uvs;
    /// ... and per face the table rows of its three corners (as F has its vertices), or no rows.
    Eigen::MatrixX3i corner_uv_faces;
};

}  // namespace genflow
