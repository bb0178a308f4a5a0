// SPDX-License-Identifier: MIT
// Data a file gives per face corner (texture coordinates, OBJ normals): collected beside the
// faces as the readers split polygons, then kept per vertex where that loses nothing.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "genflow/io/vertex_attributes.h"

namespace genflow::detail {

/// Appends the fan triangles of a polygon (corners 0, k, k+1) to `triangles`, as
/// MeshBuilder::add_polygon() splits the polygon's vertices: corner data stays aligned with
/// the faces. Polygons of fewer than 3 corners add nothing, as they add no face.
void append_fan(const std::vector<std::int64_t>& polygon, std::vector<int>& triangles);

/// The rows of `table` per vertex, when every vertex of `faces` (of `vertex_count`) meets the
/// same row values at all its corners (`corner_rows`: per face, the table rows of its corners)
/// and every vertex has a corner; nothing otherwise (a seam, or a vertex without a face).
[[nodiscard]] std::optional<Eigen::MatrixXd> per_vertex_rows(const Eigen::MatrixX3i& faces,
                                                             const Eigen::MatrixXd& table,
                                                             const Eigen::MatrixX3i& corner_rows,
                                                             Eigen::Index vertex_count);

/// Texture coordinates into `attributes`: per vertex where they are (`per_vertex`, from
/// per_vertex_rows()), else per corner (`table` rows, `corner_rows` per face), so that a seam
/// loses nothing.
void store_texture_coordinates(std::optional<Eigen::MatrixXd> per_vertex, Eigen::MatrixXd table,
                               Eigen::MatrixX3i corner_rows, VertexAttributes& attributes);

/// `triangles` (3 ints each, from append_fan()) as a #F×3 matrix.
[[nodiscard]] Eigen::MatrixX3i as_faces(const std::vector<int>& triangles);

}  // namespace genflow::detail
