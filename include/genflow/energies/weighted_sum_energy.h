// SPDX-License-Identifier: MIT
#pragma once

#include <memory>
#include <vector>

#include "genflow/energies/energy.h"

namespace genflow {

/// E = Σ_k w_k E_k. The differential is the weighted sum of the differentials; a linearization
/// exists when every term with a non-zero weight has one and no weight is negative (so that A
/// stays PSD).
class WeightedSumEnergy final : public Energy {
public:
    struct Term {
        double weight;
        std::shared_ptr<const Energy> energy;
    };

    /// \throws InvalidInput if a weight is not finite or an energy is null.
    explicit WeightedSumEnergy(std::vector<Term> terms);

    [[nodiscard]] double value(const TriangleMesh& mesh) const override;
    [[nodiscard]] VertexField differential(const TriangleMesh& mesh) const override;
    [[nodiscard]] std::optional<Linearization> linearize(const TriangleMesh& mesh) const override;

    [[nodiscard]] const std::vector<Term>& terms() const { return terms_; }

private:
    std::vector<Term> terms_;
};

}  // namespace genflow
