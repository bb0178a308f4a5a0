// SPDX-License-Identifier: MIT
#include "genflow/energies/weighted_sum_energy.h"

#include <cmath>

#include "genflow/exceptions.h"

namespace genflow {

WeightedSumEnergy::WeightedSumEnergy(std::vector<Term> terms) : terms_(std::move(terms)) {
    for (const auto& term : terms_) {
        if (!std::isfinite(term.weight) || !term.energy) {
            throw InvalidInput("WeightedSumEnergy: every term needs a finite weight and an energy");
        }
    }
}

double WeightedSumEnergy::value(const TriangleMesh& mesh) const {
    double total = 0;
    for (const auto& term : terms_) {
        total += term.weight == 0 ? 0 : term.weight * term.energy->value(mesh);
    }
    return total;
}

VertexField WeightedSumEnergy::differential(const TriangleMesh& mesh) const {
    VertexField total = VertexField::Zero(mesh.V.rows(), 3);
    for (const auto& term : terms_) {
        if (term.weight != 0) {
            total += term.weight * term.energy->differential(mesh);
        }
    }
    return total;
}

std::optional<Linearization> WeightedSumEnergy::linearize(const TriangleMesh& mesh) const {
    Linearization total{Eigen::SparseMatrix<double>(mesh.V.rows(), mesh.V.rows()),
                        VertexField::Zero(mesh.V.rows(), 3)};
    for (const auto& term : terms_) {
        if (term.weight == 0) {
            continue;
        }
        if (term.weight < 0) {
            return std::nullopt;  // −w·A is not PSD
        }
        auto part = term.energy->linearize(mesh);
        if (!part) {
            return std::nullopt;
        }
        total.A += term.weight * part->A;
        total.B += term.weight * part->B;
    }
    return total;
}

}  // namespace genflow
