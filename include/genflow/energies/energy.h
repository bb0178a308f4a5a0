// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/SparseCore>
#include <optional>

#include "genflow/mesh.h"

namespace genflow {

/// A linearization of an energy's differential around the current positions X_t (paper eq. 11):
///
///     dE/dX(X) ≈ A·X + B,
///
/// with A a #V×#V symmetric positive semi-definite matrix acting on each coordinate column and
/// B a #V×3 field, both frozen at X_t. Implicit integrators solve (G + dt·A) X' = G X − dt·B.
struct Linearization {
    Eigen::SparseMatrix<double> A;
    VertexField B;
};

/// An energy of the vertex positions (paper §2): a value and its L2 differential dE/dX, the
/// #V×3 matrix of partial derivatives, which a Metric turns into a gradient.
///
/// Write your own by overriding `value()` and `differential()`; `linearize()` is optional and
/// enables implicit integration. Implementations are stateless or cache only what depends on
/// connectivity, so const calls may run concurrently.
class Energy {
public:
    virtual ~Energy() = default;

    /// E(X) at the positions of `mesh`.
    [[nodiscard]] virtual double value(const TriangleMesh& mesh) const = 0;

    /// dE/dX at the positions of `mesh`, #V×3 (not a gradient: it has units of E per length,
    /// and turns into a velocity only through a metric).
    [[nodiscard]] virtual VertexField differential(const TriangleMesh& mesh) const = 0;

    /// dE/dX ≈ A X + B around `mesh` with A symmetric PSD, or nothing if the energy has no such
    /// linearization (then only explicit integration applies).
    [[nodiscard]] virtual std::optional<Linearization> linearize(const TriangleMesh& mesh) const {
        (void)mesh;
        return std::nullopt;
    }
};

}  // namespace genflow
