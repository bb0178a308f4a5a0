// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include "genflow/io/vertex_attributes.h"
#include "genflow/mesh.h"
#include "genflow/spatial/closest_point.h"

namespace genflow {

/// A template's per-vertex attributes carried to a target through a correspondence (one
/// SurfacePoint per template vertex, as match_correspondence() or read_correspondences() give
/// it): the template's faces are laid over the target (vertex i at correspondence[i].point), and
/// each target vertex takes the attributes of the laid-over point nearest to it: colours and
/// values interpolated over that face, a value that is a whole number at every template vertex
/// (a label: part, segment, region) from the face's nearest corner, since a blend of two labels
/// names neither. Texture coordinates, per vertex or per corner, become the target's per vertex,
/// interpolated over the face (per corner: that face's own, so a target vertex takes the side
/// of a seam its face lies on; a target face across a seam spans the gap in the texture).
/// Normals are not carried: the target has its own surface.
/// \throws InvalidInput if the correspondence or the attributes do not have a row per template
///         vertex (texture coordinates per corner: a row of table indices per face), or a mesh
///         has no face, bad indices or non-finite coordinates.
[[nodiscard]] VertexAttributes carry_attributes(const TriangleMesh& template_mesh,
                                                const VertexAttributes& attributes,
                                                const TriangleMesh& target,
                                                const std::vector<SurfacePoint>& correspondence);

}  // namespace genflow
