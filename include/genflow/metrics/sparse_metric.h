// SPDX-License-Identifier: MIT
#pragma once

#include <memory>

#include "genflow/metrics/factorization.h"
#include "genflow/metrics/metric.h"

namespace genflow {

/// A Metric whose G is a sparse #V×#V matrix acting on each coordinate column (L2, H1, H2, or
/// your own): subclasses only say how to assemble G; solving, the implicit step and fixed
/// vertices are handled here. G (and G + dt·A) are factored by CHOLMOD when available, else by
/// Eigen's SimplicialLDLT; the symbolic analysis is reused while the sparsity pattern stays the
/// same, so a flow pays for it once.
///
/// \code
///   // A metric that penalizes motion of heavy vertices twice as much:
///   class DoubleMass final : public genflow::SparseMetric {
///       Eigen::SparseMatrix<double> assemble(const genflow::TriangleMesh& mesh) const override {
///           return 2.0 * genflow::mass_matrix(mesh, genflow::MassType::Full);
///       }
///   };
/// \endcode
class SparseMetric : public Metric {
public:
    explicit SparseMetric(Factorization factorization = Factorization::BySize);
    ~SparseMetric() override;
    SparseMetric(SparseMetric&&) noexcept;
    SparseMetric& operator=(SparseMetric&&) noexcept;

    void update(const TriangleMesh& mesh) final;
    void update_alongside(const TriangleMesh& mesh, const std::function<void()>& task) final;
    [[nodiscard]] VertexField gradient(const VertexField& dEdX) const final;
    [[nodiscard]] VertexField apply(const VertexField& U) const final;
    [[nodiscard]] VertexField shifted_gradient(const Eigen::SparseMatrix<double>& A, double dt,
                                               const VertexField& R) final;

    /// G at the mesh last given to `update()` (without the fixed-vertex modification).
    [[nodiscard]] const Eigen::SparseMatrix<double>& matrix() const;

    /// How many symbolic factorizations were computed so far (G and G + dt·A together).
    [[nodiscard]] int symbolic_analyses() const;

protected:
    /// G at the positions of `mesh`: symmetric positive definite, #V×#V. Called by `update()`
    /// after the mesh was checked (indices in range, finite positions, at least one face).
    [[nodiscard]] virtual Eigen::SparseMatrix<double> assemble(const TriangleMesh& mesh) const = 0;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace genflow
