// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <vector>

#include "genflow/matching/landmarks.h"
#include "genflow/mesh.h"

namespace genflow {

/// Reads a match's landmarks (`genflow match --landmarks`): one per line, **0-based** indices,
///
///     i x y z [w]   template vertex i goes to the point (x, y, z) of the target's frame
///     i j [w]       template vertex i goes to target vertex j
///
/// with an optional positive weight w (Landmark::weight; 1 if left out), the landmark's share
/// of the landmarks' term relative to the others'.
/// Blank lines are skipped, and a `#` starts a comment that runs to the end of its line.
/// `template_vertices` is the template's vertex count; `target` gives the vertices `j` name.
/// \throws IoError "<path>: line N: <problem>" for a line of another shape, a token that is not
///         a number, an index out of range, a non-finite coordinate or a weight that is not
///         positive; "<path>: ..." if the file cannot be read or holds no landmark.
[[nodiscard]] std::vector<Landmark> read_landmarks(const std::filesystem::path& path,
                                                   Eigen::Index template_vertices,
                                                   const TriangleMesh& target);

}  // namespace genflow
