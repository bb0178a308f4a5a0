// SPDX-License-Identifier: MIT
#include "genflow/operators/cotan_stiffness.h"

#include <vector>

#include "operators/triangle.h"

namespace genflow {

Eigen::SparseMatrix<double> cotan_stiffness(const TriangleMesh& mesh, const CotanOptions& options) {
    detail::require_valid_mesh(mesh, "cotan_stiffness");
    if (!detail::finite_above(options.max_cotangent, 0)) {
        throw InvalidInput("cotan_stiffness: max_cotangent must be positive");
    }
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<std::size_t>(12 * mesh.F.rows()));
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        // Degenerate faces still add (zero) entries: the sparsity pattern then depends only on
        // the connectivity, and a flow's symbolic factorization stays valid.
        const detail::Triangle t(mesh, f);
        const Eigen::Vector3d cots =
            t.degenerate() ? Eigen::Vector3d::Zero() : t.bounded_cots(options.max_cotangent);
        for (int k = 0; k < 3; ++k) {
            // The angle at corner k is opposite the edge (k+1, k+2).
            const double w = 0.5 * cots[k];
            const int i = mesh.F(f, (k + 1) % 3);
            const int j = mesh.F(f, (k + 2) % 3);
            triplets.emplace_back(i, j, -w);
            triplets.emplace_back(j, i, -w);
            triplets.emplace_back(i, i, w);
            triplets.emplace_back(j, j, w);
        }
    }
    Eigen::SparseMatrix<double> K(mesh.V.rows(), mesh.V.rows());
    K.setFromTriplets(triplets.begin(), triplets.end());
    return K;
}

}  // namespace genflow
