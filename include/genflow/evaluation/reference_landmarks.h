// SPDX-License-Identifier: MIT
#pragma once

#include <vector>

#include "genflow/matching/landmarks.h"
#include "genflow/mesh.h"

namespace genflow {

/// `count` landmarks of a benchmark pair taken from its ground truth, as a user would click
/// them: reference points spread over the template by farthest-point sampling (Euclidean, from
/// reference point 0, so the same pair gets the same landmarks), each template vertex given its
/// reference point's vertex on the target. `from_reference[k]` and `to_reference[k]` are the
/// vertices of reference point k on the template and the target (read_reference_points()).
/// \throws InvalidInput if the reference lists differ in size, name a vertex outside their mesh,
///         or hold fewer than `count` points, or `count` < 1.
[[nodiscard]] std::vector<Landmark> reference_landmarks(
    const TriangleMesh& from, const std::vector<Eigen::Index>& from_reference,
    const TriangleMesh& to, const std::vector<Eigen::Index>& to_reference, int count);

}  // namespace genflow
