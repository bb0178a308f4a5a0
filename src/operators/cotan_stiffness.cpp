// SPDX-License-Identifier: MIT
#include "genflow/operators/cotan_stiffness.h"

#include <vector>

#include "operators/cotan_entries.h"
#include "operators/triangle.h"

namespace genflow {

Eigen::SparseMatrix<double> cotan_stiffness(const TriangleMesh& mesh, const CotanOptions& options) {
    detail::require_valid_mesh(mesh, "cotan_stiffness");
    if (!detail::finite_above(options.max_cotangent, 0)) {
        throw InvalidInput("cotan_stiffness: max_cotangent must be positive");
    }
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<std::size_t>(detail::kCotanEntriesPerFace * mesh.F.rows()));
    detail::for_each_cotan_entry(
        mesh, options, [&](int i, int j, double value) { triplets.emplace_back(i, j, value); });
    Eigen::SparseMatrix<double> K(mesh.V.rows(), mesh.V.rows());
    K.setFromTriplets(triplets.begin(), triplets.end());
    return K;
}

}  // namespace genflow
