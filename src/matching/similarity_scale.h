// SPDX-License-Identifier: MIT
// The scale of a match's starts. Bending keeps a shape's area, so the starts take the template
// to the target's size by the ratio of their areas; but a rough surface (a scan's noise) has
// more area than the shape it samples, and the template would start too large, at lengths the
// stretching energy then holds. The enclosed volume hardly changes with noise, and is the
// shape's when its holes are small.
#pragma once

#include <optional>

#include "genflow/mesh.h"

namespace genflow::detail {

/// The volume enclosed by `mesh` with its holes capped by cones to the centre of its boundary
/// (its absolute value: any orientation); the plain enclosed volume of a closed mesh.
[[nodiscard]] double capped_volume(const TriangleMesh& mesh);

/// The total length of the edges of `mesh` used by one face only.
[[nodiscard]] double boundary_length(const TriangleMesh& mesh);

/// The scale that gives `from` the enclosed volume of `to`, where their areas mislead: when
/// `area_scale` (√ of the areas' ratio) is more than kAreaVolumeTolerance off it, both meshes
/// having short boundaries (so that their capped volumes are their shapes'); else
/// std::nullopt, and the area's scale stands.
[[nodiscard]] std::optional<double> volume_scale_where_areas_mislead(const TriangleMesh& from,
                                                                     const TriangleMesh& to,
                                                                     double area_scale);

/// How far the area's scale may be from the volume's before the volume's is taken: more than
/// the two differ between clean poses of one shape (2.1 % measured), less than noise along the
/// normals inflates the area (the volume moves far less; docs/measurements.md, "Scale").
inline constexpr double kAreaVolumeTolerance = 0.05;

/// Boundary length over √area up to which a mesh's capped volume is its shape's: above small
/// scanner holes and an open wrist (0.1–1.04 measured), below a shape cut through its middle.
inline constexpr double kShortBoundary = 1.5;

}  // namespace genflow::detail
