// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

#include "genflow/io/vertex_attributes.h"

namespace genflow {

/// The colours of `values` on viridis (van der Walt and Smith's perceptually uniform map, dark
/// purple → blue → green → yellow, readable in grey and by colour-blind readers): `low` and
/// below are its first colour, `high` and above its last, linear in between. A non-finite value
/// is mid grey.
/// \throws InvalidInput unless low < high, both finite.
[[nodiscard]] VertexColors viridis_colors(const Eigen::VectorXd& values, double low, double high);

}  // namespace genflow
