// SPDX-License-Identifier: MIT
#include "operators/stiffness_pattern.h"

#include <algorithm>

#include "genflow/exceptions.h"
#include "operators/cotan_entries.h"
#include "operators/triangle.h"

namespace genflow::detail {

StiffnessPattern::StiffnessPattern(const TriangleMesh& mesh)
    : vertices_(mesh.V.rows()), faces_(mesh.F) {
    std::vector<Eigen::Triplet<double>> positions;
    positions.reserve(static_cast<std::size_t>(kCotanEntriesPerFace * mesh.F.rows() + vertices_));
    for_each_cotan_entry(mesh, CotanOptions{},
                         [&](int i, int j, double) { positions.emplace_back(i, j, 1.0); });
    const std::size_t stiffness_entries = positions.size();
    for (Eigen::Index i = 0; i < vertices_; ++i) {
        positions.emplace_back(static_cast<int>(i), static_cast<int>(i), 1.0);
    }
    pattern_.resize(vertices_, vertices_);
    pattern_.setFromTriplets(positions.begin(), positions.end());
    pattern_.makeCompressed();

    // Rows are sorted within each column of a compressed matrix.
    const auto slot_of = [&](Eigen::Index row, Eigen::Index column) {
        const int* first = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[column];
        const int* last = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[column + 1];
        return static_cast<Eigen::Index>(std::lower_bound(first, last, static_cast<int>(row)) -
                                         pattern_.innerIndexPtr());
    };
    entry_slot_.resize(stiffness_entries);
    in_stiffness_.assign(static_cast<std::size_t>(pattern_.nonZeros()), 0);
    for (std::size_t e = 0; e < stiffness_entries; ++e) {
        entry_slot_[e] = slot_of(positions[e].row(), positions[e].col());
        in_stiffness_[static_cast<std::size_t>(entry_slot_[e])] = 1;
    }
    diagonal_slot_.resize(static_cast<std::size_t>(vertices_));
    for (Eigen::Index i = 0; i < vertices_; ++i) {
        diagonal_slot_[static_cast<std::size_t>(i)] = slot_of(i, i);
    }
}

bool StiffnessPattern::fits(const TriangleMesh& mesh) const {
    return mesh.V.rows() == vertices_ && mesh.F.rows() == faces_.rows() && mesh.F == faces_;
}

Eigen::SparseMatrix<double> StiffnessPattern::diagonal_plus_stiffness(
    const TriangleMesh& mesh, const Eigen::VectorXd& diagonal, double lambda,
    const CotanOptions& options) const {
    if (!fits(mesh) || diagonal.size() != vertices_) {
        throw InvalidInput("StiffnessPattern: the mesh or the diagonal does not fit the pattern");
    }
    const auto slots = static_cast<std::size_t>(pattern_.nonZeros());
    // K's entries, each summed in the order setFromTriplets() sums duplicates: the first one
    // as it is (−0 + v = v for every v, signed zeros included), then the others in turn.
    std::vector<double> stiffness(slots, -0.0);
    std::size_t e = 0;
    for_each_cotan_entry(mesh, options, [&](int, int, double value) {
        stiffness[static_cast<std::size_t>(entry_slot_[e++])] += value;
    });
    Eigen::SparseMatrix<double> sum = pattern_;
    double* values = sum.valuePtr();
    // Eigen's sum of sparse matrices adds 0 for an entry missing on one side: 0 + λk off the
    // diagonal (which keeps the sign of a zero as Eigen does), d_i + λk or d_i + 0 on it.
    for (std::size_t s = 0; s < slots; ++s) {
        values[s] = in_stiffness_[s] != 0 ? 0.0 + lambda * stiffness[s] : 0.0;
    }
    for (Eigen::Index i = 0; i < vertices_; ++i) {
        const auto s = static_cast<std::size_t>(diagonal_slot_[static_cast<std::size_t>(i)]);
        values[s] = diagonal[i] + (in_stiffness_[s] != 0 ? lambda * stiffness[s] : 0.0);
    }
    return sum;
}

Eigen::SparseMatrix<double> StiffnessPatternCache::diagonal_plus_stiffness(
    const TriangleMesh& mesh, const Eigen::VectorXd& diagonal, double lambda,
    const CotanOptions& options, const char* caller) {
    const std::lock_guard lock(mutex_);
    if (!pattern_ || !pattern_->fits(mesh)) {
        require_valid_mesh(mesh, caller);  // a mesh that fits has valid indices
        pattern_.emplace(mesh);
    }
    return pattern_->diagonal_plus_stiffness(mesh, diagonal, lambda, options);
}

}  // namespace genflow::detail
