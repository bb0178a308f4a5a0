// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <vector>

namespace genflow {

/// Reads the reference points of a correspondence benchmark's shape (a `.vts` file, as FAUST_r,
/// SCAPE_r and SHREC'19_r publish them): line k holds the **1-based** index of the shape's
/// vertex at reference point k, the same point of every shape of the set. Blank lines and lines
/// starting with `#` are skipped. Returns 0-based vertex indices, one per reference point.
/// \throws IoError "<path>: line N: <problem>" for a token that is not an integer, an index
///         outside [1, vertex_count], or a line with more than one token; "<path>: ..." if the
///         file cannot be read or holds no reference point.
[[nodiscard]] std::vector<Eigen::Index> read_reference_points(const std::filesystem::path& path,
                                                              Eigen::Index vertex_count);

}  // namespace genflow
