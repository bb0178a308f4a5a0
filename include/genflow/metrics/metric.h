// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/SparseCore>
#include <functional>
#include <vector>

#include "genflow/mesh.h"

namespace genflow {

/// An inner product on deformation fields of a triangle mesh (paper §3, eqs. 7–9):
///
///     <U, W>_L = trace(Uᵀ G W),   G = M·L symmetric positive definite,
///
/// where M is the mass matrix and L the operator that defines the metric. A Metric turns the
/// differential of an energy, dE/dX (`Energy::differential()`), into the generalized gradient
/// ∇_L E = G⁻¹ dE/dX (eq. 8), along which the integrators step. (Not to be confused with the
/// surface's own metric, its edge lengths.)
///
/// Implementations cache a factorization of G: build one Metric per flow and call `update()`
/// whenever the vertex positions change. Const members may run concurrently.
///
/// **Fixed vertices.** With `set_fixed_vertices()`, gradients are taken in the subspace of
/// fields that vanish at the fixed vertices: the rows and columns of G for those vertices are
/// replaced by the identity and the right-hand side is zeroed there, so fixed vertices never
/// move and the others feel them as boundary conditions.
class Metric {
public:
    virtual ~Metric() = default;

    /// Assembles G at the current positions of `mesh` and factors it.
    /// \throws InvalidInput if `mesh` is empty, F indexes outside V, or the fixed-vertex mask
    ///                      has the wrong size.
    /// \throws SolverError  if G is not numerically positive definite.
    virtual void update(const TriangleMesh& mesh) = 0;

    /// update(mesh), with `task` run meanwhile on a thread the update leaves idle where it has
    /// one (a factorization in two unequal halves: the smaller one's thread, once that half is
    /// factored), else after it. A flow computes the energy's differential so, which needs the
    /// mesh only. `task` (none if empty) must not use this metric; what it throws is rethrown
    /// after the update.
    /// \throws as update().
    virtual void update_alongside(const TriangleMesh& mesh, const std::function<void()>& task) {
        update(mesh);
        if (task) {
            task();
        }
    }

    /// G⁻¹·dEdX, the gradient of an energy in this metric (eq. 8).
    /// \param dEdX  #V×3 differential of the energy at the mesh last given to `update()`.
    /// \throws InvalidInput if `update()` was never called or the row count differs.
    [[nodiscard]] virtual VertexField gradient(const VertexField& dEdX) const = 0;

    /// G·U (the metric applied to a field): <U, W>_L = trace(Uᵀ apply(W)).
    /// \throws InvalidInput as `gradient()`.
    [[nodiscard]] virtual VertexField apply(const VertexField& U) const = 0;

    /// (G + dt·A)⁻¹·R, the solve of the implicit step (eq. 11): with R = dE/dX(X_t) = A X_t + B,
    /// X_{t+dt} = X_t − dt·(G + dt·A)⁻¹ R is the solution of (G + dt·A) X' = G X_t − dt·B.
    /// Equivalently, an explicit step in the metric G + dt·A (docs/formulas.md §2).
    /// \param A  #V×#V symmetric PSD (`Linearization::A`) acting on each coordinate.
    /// \throws InvalidInput if sizes differ or dt is negative or not finite.
    /// \throws SolverError  if the system cannot be solved.
    [[nodiscard]] virtual VertexField shifted_gradient(const Eigen::SparseMatrix<double>& A,
                                                       double dt, const VertexField& R) = 0;

    /// Vertices that must not move (an empty mask means none); used from the next `update()`.
    void set_fixed_vertices(std::vector<bool> fixed) { fixed_ = std::move(fixed); }
    [[nodiscard]] const std::vector<bool>& fixed_vertices() const { return fixed_; }

protected:
    std::vector<bool> fixed_;
};

}  // namespace genflow
