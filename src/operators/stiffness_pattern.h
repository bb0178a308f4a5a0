// SPDX-License-Identifier: MIT
// The sparsity pattern of D + λK (D diagonal, K the cotan stiffness) for one connectivity, so
// that a flow which re-assembles the H1 metric at every step (the same faces, moved vertices)
// writes values into fixed slots instead of sorting 12 triplets per face. Assembled from
// triplets, M + λK took about 40 % of an H1 metric's update() at the size of a match's
// coarsest level (bench/flow_bench, 642 vertices: 239 of 619 µs); one H1 step went 683 →
// 554 µs with this.
#pragma once

#include <Eigen/SparseCore>
#include <mutex>
#include <optional>
#include <vector>

#include "genflow/mesh.h"
#include "genflow/operators/cotan_stiffness.h"

namespace genflow::detail {

class StiffnessPattern {
public:
    /// The pattern of `mesh`'s faces on its vertices (a valid mesh: require_valid_mesh()).
    explicit StiffnessPattern(const TriangleMesh& mesh);

    /// Whether `mesh` has the vertex count and faces this pattern was built for.
    [[nodiscard]] bool fits(const TriangleMesh& mesh) const;

    /// diag(`diagonal`) + λ·cotan_stiffness(mesh, options) for a `mesh` that fits(), equal to
    /// the bit to that sum of Eigen sparse matrices: each entry of K is summed in
    /// cotan_stiffness()'s order (that of setFromTriplets()), the sum of the two matrices
    /// adds 0 where one has no entry, as Eigen's does.
    [[nodiscard]] Eigen::SparseMatrix<double> diagonal_plus_stiffness(
        const TriangleMesh& mesh, const Eigen::VectorXd& diagonal, double lambda,
        const CotanOptions& options = {}) const;

private:
    Eigen::Index vertices_ = 0;
    Eigen::MatrixX3i faces_;
    Eigen::SparseMatrix<double> pattern_;  // compressed, column-major, every diagonal entry
    std::vector<int> edge_slot_;      // per corner of each face: the slots of (i, j) and (j, i)
    std::vector<int> diagonal_slot_;  // per vertex
    // Per slot: off the diagonal (K always has an entry there), or on it, with or without one.
    enum class SlotKind : char { OffDiagonal, Diagonal, DiagonalWithStiffness };
    std::vector<SlotKind> slot_kind_;
};

/// The StiffnessPattern of the last connectivity assembled, rebuilt when the faces change, for
/// assemblers that are const and may be called from several threads (one lock per assembly).
class StiffnessPatternCache {
public:
    /// StiffnessPattern::diagonal_plus_stiffness() for any valid mesh; `caller` names the
    /// assembler in the error of an invalid one.
    [[nodiscard]] Eigen::SparseMatrix<double> diagonal_plus_stiffness(
        const TriangleMesh& mesh, const Eigen::VectorXd& diagonal, double lambda,
        const CotanOptions& options, const char* caller);

private:
    std::mutex mutex_;
    std::optional<StiffnessPattern> pattern_;
};

}  // namespace genflow::detail
