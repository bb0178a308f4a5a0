// SPDX-License-Identifier: MIT
#pragma once

#include "genflow/energies/energy.h"

namespace genflow {

/// Signed enclosed volume E = V(X) = (1/6) Σ_f x_a·(x_b × x_c) (docs/formulas.md §1); its
/// differential is `enclosed_volume_gradient()`. Add it with a weight to another energy to inflate
/// (negative weight) or deflate a shape. It has no PSD linearization, so flows of it are explicit.
///
/// \note Meaningful only on closed meshes; on inward-oriented meshes the value is negative and
///       the differential points inward, so "decrease V" still means "grow the |V|" there: flip
///       the faces first (`validate()` reports `inward_oriented`).
class EnclosedVolumeEnergy final : public Energy {
public:
    [[nodiscard]] double value(const TriangleMesh& mesh) const override;
    [[nodiscard]] VertexField differential(const TriangleMesh& mesh) const override;
};

}  // namespace genflow
