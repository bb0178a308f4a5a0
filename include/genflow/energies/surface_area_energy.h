// SPDX-License-Identifier: MIT
#pragma once

#include <memory>

#include "genflow/energies/energy.h"
#include "genflow/operators/cotan_stiffness.h"

namespace genflow {

/// Surface area E = Σ_f A_f. Its L2 flow is mean-curvature flow, its H1 flow implicit fairing
/// (paper §4).
///
/// - differential: ∂A/∂X = K X (`surface_area_gradient()`), the mean-curvature normal times the
///   vertex areas.
/// - linearization: A = K (the cotan stiffness matrix at X_t, symmetric PSD, singular), B = 0
///   (docs/formulas.md §2: A is PSD, not PD, and the implicit system is still SPD).
///
/// \note Works on any mesh `cotan_stiffness()` accepts; the linearization is exact at X_t up to
///       the cotangent clamp of needle triangles.
class SurfaceAreaEnergy final : public Energy {
public:
    explicit SurfaceAreaEnergy(CotanOptions options = {});
    ~SurfaceAreaEnergy() override;
    /// A copy has the options and its own (empty) cache of the stiffness pattern.
    SurfaceAreaEnergy(const SurfaceAreaEnergy& other);
    SurfaceAreaEnergy& operator=(const SurfaceAreaEnergy& other);
    SurfaceAreaEnergy(SurfaceAreaEnergy&&) noexcept;
    SurfaceAreaEnergy& operator=(SurfaceAreaEnergy&&) noexcept;

    [[nodiscard]] double value(const TriangleMesh& mesh) const override;
    [[nodiscard]] VertexField differential(const TriangleMesh& mesh) const override;
    [[nodiscard]] std::optional<Linearization> linearize(const TriangleMesh& mesh) const override;

private:
    CotanOptions options_;
    // The sparsity pattern of K for the last connectivity linearized: a flow linearizes the
    // same faces at every step.
    struct PatternCache;
    std::unique_ptr<PatternCache> pattern_cache_;
};

}  // namespace genflow
