// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "genflow/mesh.h"

namespace genflow {

/// What one camera sees of a mesh, as the benchmarks of partial matching make a single-view
/// scan: the faces that face the camera (normal · view < 0), occluded ones included. The
/// vertices are all kept, in order (those of no kept face unreferenced), so a vertex index of
/// the view is one of the mesh.
/// \param view  the direction the camera looks along, any length > 0.
/// \throws InvalidInput if the mesh is invalid or `view` is zero or not finite.
[[nodiscard]] TriangleMesh single_view(const TriangleMesh& mesh, const Eigen::Vector3d& view);

/// A direction uniform on the sphere drawn from `seed` (the same direction for the same seed).
[[nodiscard]] Eigen::Vector3d view_direction(std::uint64_t seed);

}  // namespace genflow
