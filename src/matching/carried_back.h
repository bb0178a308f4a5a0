// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

#include "genflow/mesh.h"
#include "genflow/mesh/repair.h"

namespace genflow::detail {

/// Positions for every vertex of the input of repair_surface() from `positions` of the repaired
/// surface's vertices (a deformation of it): a carried vertex takes its repaired vertex's
/// position; any other (on no face, or in a component left out) moves by the displacement of
/// the carried vertex nearest to it at rest, so that loose pieces follow the surface beside
/// them.
/// \throws InvalidInput if `positions` does not have a row per repaired vertex.
[[nodiscard]] Eigen::MatrixX3d carried_back(const RepairedSurface& repaired,
                                            const Eigen::MatrixX3d& input_rest,
                                            const Eigen::MatrixX3d& positions);

/// The counterparts (MatchResult::counterparts) of every vertex of the input of
/// repair_surface() from `counterparts` of the repaired surface's vertices: a carried vertex
/// takes its repaired vertex's; any other the closest point of `target` to `deformed` (the
/// input's vertices as carried_back() put them).
/// \throws InvalidInput if `counterparts` does not have a row per repaired vertex or `deformed`
///         one per input vertex.
[[nodiscard]] Eigen::MatrixX3d carried_counterparts(const RepairedSurface& repaired,
                                                    const Eigen::MatrixX3d& counterparts,
                                                    const Eigen::MatrixX3d& deformed,
                                                    const TriangleMesh& target);

}  // namespace genflow::detail
