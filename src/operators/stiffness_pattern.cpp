// SPDX-License-Identifier: MIT
#include "operators/stiffness_pattern.h"

#include <algorithm>
#include <numeric>
#include <utility>

#include "genflow/exceptions.h"
#include "operators/cotan_entries.h"
#include "operators/triangle.h"

namespace genflow::detail {

namespace {

// The off-diagonal entries the faces put in each column of K: per corner k of face f, with
// (i, j) the edge opposite it, row i of column j and row j of column i, which are edge slots
// 2(3f + k) and 2(3f + k) + 1. Bucketed by column (counting sort): `first` the column starts,
// `rows` and `edge_slots` the entries.
struct ColumnEntries {
    std::vector<int> first;
    std::vector<int> rows;
    std::vector<int> edge_slots;

    ColumnEntries(const Eigen::MatrixX3i& faces, Eigen::Index vertices)
        : first(static_cast<std::size_t>(vertices) + 1, 0),
          rows(static_cast<std::size_t>(6 * faces.rows())),
          edge_slots(rows.size()) {
        for (Eigen::Index f = 0; f < faces.rows(); ++f) {
            for (int k = 0; k < 3; ++k) {
                first[static_cast<std::size_t>(faces(f, k)) + 1] += 2;
            }
        }
        std::partial_sum(first.begin(), first.end(), first.begin());
        std::vector<int> end(first.begin(), first.end() - 1);
        const auto add = [&](int column, int row, Eigen::Index edge_slot) {
            const auto at = static_cast<std::size_t>(end[static_cast<std::size_t>(column)]++);
            rows[at] = row;
            edge_slots[at] = static_cast<int>(edge_slot);
        };
        for (Eigen::Index f = 0; f < faces.rows(); ++f) {
            for (int k = 0; k < 3; ++k) {
                const auto [i, j] = opposite_edge(faces, f, k);
                add(j, i, 2 * (3 * f + k));
                add(i, j, 2 * (3 * f + k) + 1);
            }
        }
    }
};

// The compressed columns of K + D (each column's rows sorted, without repeats) and the slots of
// the diagonal and of the faces' entries in them, each read from a table of its column's rows
// (a binary search per entry was most of the time).
struct Columns {
    std::vector<int> starts{0};
    std::vector<int> rows;
    std::vector<int> diagonal_slot;
    std::vector<int> edge_slot;

    Columns(const ColumnEntries& entries, Eigen::Index vertices)
        : diagonal_slot(static_cast<std::size_t>(vertices)), edge_slot(entries.rows.size()) {
        rows.reserve(entries.rows.size() / 2 + static_cast<std::size_t>(vertices));
        std::vector<int> slot_of_row(static_cast<std::size_t>(vertices));
        std::vector<int> column_seen(static_cast<std::size_t>(vertices), -1);  // per row
        std::vector<int> column;
        for (int v = 0; v < static_cast<int>(vertices); ++v) {
            const auto begin = static_cast<std::size_t>(entries.first[static_cast<std::size_t>(v)]);
            const auto end =
                static_cast<std::size_t>(entries.first[static_cast<std::size_t>(v) + 1]);
            column.assign(1, v);
            column_seen[static_cast<std::size_t>(v)] = v;
            for (std::size_t e = begin; e < end; ++e) {  // an interior edge comes twice
                const int row = entries.rows[e];
                if (std::exchange(column_seen[static_cast<std::size_t>(row)], v) != v) {
                    column.push_back(row);
                }
            }
            std::sort(column.begin(), column.end());
            for (const int row : column) {
                slot_of_row[static_cast<std::size_t>(row)] = static_cast<int>(rows.size());
                rows.push_back(row);
            }
            starts.push_back(static_cast<int>(rows.size()));
            diagonal_slot[static_cast<std::size_t>(v)] = slot_of_row[static_cast<std::size_t>(v)];
            for (std::size_t e = begin; e < end; ++e) {
                edge_slot[static_cast<std::size_t>(entries.edge_slots[e])] =
                    slot_of_row[static_cast<std::size_t>(entries.rows[e])];
            }
        }
    }
};

}  // namespace

StiffnessPattern::StiffnessPattern(const TriangleMesh& mesh)
    : vertices_(mesh.V.rows()), faces_(mesh.F) {
    // The pattern setFromTriplets() gives K's entries and the diagonal, built per column from
    // the faces directly (sorting 12 triplets a face cost as much as a fairing step's
    // assembly).
    const ColumnEntries entries(mesh.F, vertices_);
    Columns columns(entries, vertices_);
    const std::vector<int>& rows = columns.rows;
    diagonal_slot_ = std::move(columns.diagonal_slot);
    edge_slot_ = std::move(columns.edge_slot);
    const std::vector<int>& starts = columns.starts;
    pattern_.resize(vertices_, vertices_);
    pattern_.resizeNonZeros(static_cast<Eigen::Index>(rows.size()));
    std::copy(starts.begin(), starts.end(), pattern_.outerIndexPtr());
    std::copy(rows.begin(), rows.end(), pattern_.innerIndexPtr());
    std::fill_n(pattern_.valuePtr(), rows.size(), -0.0);

    // A diagonal entry has a stiffness part where its vertex is on a face (on two of the
    // face's opposite edges).
    slot_kind_.assign(rows.size(), SlotKind::OffDiagonal);
    for (Eigen::Index v = 0; v < vertices_; ++v) {
        const bool on_a_face = entries.first[static_cast<std::size_t>(v) + 1] >
                               entries.first[static_cast<std::size_t>(v)];
        slot_kind_[static_cast<std::size_t>(diagonal_slot_[static_cast<std::size_t>(v)])] =
            on_a_face ? SlotKind::DiagonalWithStiffness : SlotKind::Diagonal;
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
