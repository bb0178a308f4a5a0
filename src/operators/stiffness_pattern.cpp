// SPDX-License-Identifier: MIT
#include "operators/stiffness_pattern.h"

#include <algorithm>

#include "genflow/exceptions.h"
#include "operators/cotan_entries.h"
#include "operators/triangle.h"

namespace genflow::detail {

namespace {

// Per vertex, its neighbours through the faces' edges and itself, sorted and without repeats:
// the rows of its column in K + D. Returned as column starts and rows, as in a compressed
// column-major matrix.
void columns_of_faces(const Eigen::MatrixX3i& faces, Eigen::Index vertices,
                      std::vector<int>& starts, std::vector<int>& rows) {
    std::vector<int> count(static_cast<std::size_t>(vertices) + 1, 1);  // the diagonal
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            count[static_cast<std::size_t>(faces(f, k))] += 2;  // the edges on either side
        }
    }
    std::vector<int> first(static_cast<std::size_t>(vertices) + 1, 0);
    for (Eigen::Index v = 0; v < vertices; ++v) {
        first[static_cast<std::size_t>(v) + 1] =
            first[static_cast<std::size_t>(v)] + count[static_cast<std::size_t>(v)];
    }
    std::vector<int> candidates(static_cast<std::size_t>(first.back()));
    std::vector<int> end(first.begin(), first.end() - 1);
    const auto add = [&](int column, int row) {
        candidates[static_cast<std::size_t>(end[static_cast<std::size_t>(column)]++)] = row;
    };
    for (Eigen::Index v = 0; v < vertices; ++v) {
        add(static_cast<int>(v), static_cast<int>(v));
    }
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            add(faces(f, k), faces(f, (k + 1) % 3));
            add(faces(f, k), faces(f, (k + 2) % 3));
        }
    }
    starts.assign(static_cast<std::size_t>(vertices) + 1, 0);
    rows.clear();
    rows.reserve(candidates.size());
    for (Eigen::Index v = 0; v < vertices; ++v) {
        const auto begin = candidates.begin() + first[static_cast<std::size_t>(v)];
        const auto stop = candidates.begin() + end[static_cast<std::size_t>(v)];
        std::sort(begin, stop);
        rows.insert(rows.end(), begin, std::unique(begin, stop));
        starts[static_cast<std::size_t>(v) + 1] = static_cast<int>(rows.size());
    }
}

}  // namespace

StiffnessPattern::StiffnessPattern(const TriangleMesh& mesh)
    : vertices_(mesh.V.rows()), faces_(mesh.F) {
    // The pattern setFromTriplets() gives K's entries and the diagonal, built per column from
    // the faces directly (sorting 12 triplets a face cost as much as a fairing step's
    // assembly).
    std::vector<int> starts;
    std::vector<int> rows;
    columns_of_faces(mesh.F, vertices_, starts, rows);
    pattern_.resize(vertices_, vertices_);
    pattern_.resizeNonZeros(static_cast<Eigen::Index>(rows.size()));
    std::copy(starts.begin(), starts.end(), pattern_.outerIndexPtr());
    std::copy(rows.begin(), rows.end(), pattern_.innerIndexPtr());
    std::fill_n(pattern_.valuePtr(), rows.size(), -0.0);

    // Rows are sorted within each column.
    const auto slot_of = [&](int row, int column) {
        const int* begin = rows.data() + starts[static_cast<std::size_t>(column)];
        const int* stop = rows.data() + starts[static_cast<std::size_t>(column) + 1];
        return static_cast<int>(std::lower_bound(begin, stop, row) - rows.data());
    };
    diagonal_slot_.resize(static_cast<std::size_t>(vertices_));
    for (Eigen::Index i = 0; i < vertices_; ++i) {
        diagonal_slot_[static_cast<std::size_t>(i)] =
            slot_of(static_cast<int>(i), static_cast<int>(i));
    }
    // Of the four entries per corner, (i, j) and (j, i) need their slots; (i, i) and (j, j)
    // are the diagonal's.
    edge_slot_.clear();
    edge_slot_.reserve(static_cast<std::size_t>(6 * mesh.F.rows()));
    slot_kind_.assign(rows.size(), SlotKind::OffDiagonal);
    for (const int slot : diagonal_slot_) {
        slot_kind_[static_cast<std::size_t>(slot)] = SlotKind::Diagonal;
    }
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            const auto [i, j] = opposite_edge(mesh.F, f, k);
            edge_slot_.push_back(slot_of(i, j));
            edge_slot_.push_back(slot_of(j, i));
            for (const int vertex : {i, j}) {
                slot_kind_[static_cast<std::size_t>(
                    diagonal_slot_[static_cast<std::size_t>(vertex)])] =
                    SlotKind::DiagonalWithStiffness;
            }
        }
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
    // K's entries, summed in place in the order setFromTriplets() sums duplicates: the first
    // one as it is (the pattern's −0 + v = v for every v, signed zeros included), then the
    // others in turn (for_each_cotan_entry()'s four a corner).
    Eigen::SparseMatrix<double> sum = pattern_;
    double* values = sum.valuePtr();
    const int* edge_slot = edge_slot_.data();
    for_each_cotan_weight(mesh, options, [&](int i, int j, double w) {
        values[edge_slot[0]] += -w;
        values[edge_slot[1]] += -w;
        values[diagonal_slot_[static_cast<std::size_t>(i)]] += w;
        values[diagonal_slot_[static_cast<std::size_t>(j)]] += w;
        edge_slot += 2;
    });
    // Eigen's sum of sparse matrices adds 0 for an entry missing on one side: 0 + λk off the
    // diagonal (which keeps the sign of a zero as Eigen does), d_i + λk or d_i + 0 on it.
    const int* rows = sum.innerIndexPtr();
    for (Eigen::Index s = 0; s < sum.nonZeros(); ++s) {
        switch (slot_kind_[static_cast<std::size_t>(s)]) {
            case SlotKind::OffDiagonal:
                values[s] = 0.0 + lambda * values[s];
                break;
            case SlotKind::Diagonal:
                values[s] = diagonal[rows[s]] + 0.0;
                break;
            case SlotKind::DiagonalWithStiffness:
                values[s] = diagonal[rows[s]] + lambda * values[s];
                break;
        }
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
