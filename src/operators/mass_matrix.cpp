// SPDX-License-Identifier: MIT
#include "genflow/operators/mass_matrix.h"

#include <vector>

#include "operators/triangle.h"

namespace genflow {

namespace {

// Mixed Voronoi area of each corner of a non-degenerate triangle (Meyer et al. 2002, Fig. 4).
Eigen::Vector3d voronoi_corner_areas(const detail::Triangle& t) {
    const double area = t.area();
    Eigen::Vector3d corner_area;
    for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d u = t.x[(k + 1) % 3] - t.x[k];
        const Eigen::Vector3d v = t.x[(k + 2) % 3] - t.x[k];
        if (u.dot(v) < 0) {  // obtuse at k
            // A_f/2 at the obtuse corner, A_f/4 at the two others.
            return Eigen::Vector3d::Constant(area / 4) + Eigen::Vector3d::Unit(k) * (area / 4);
        }
    }
    // Non-obtuse: (|x_i−x_j|² cot γ_k + |x_i−x_k|² cot γ_j)/8, with unclamped cotangents
    // (they are bounded here: all angles lie in (0°, 90°]).
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        const int k = (i + 2) % 3;
        corner_area[i] = ((t.x[i] - t.x[j]).squaredNorm() * t.cot(k) +
                          (t.x[i] - t.x[k]).squaredNorm() * t.cot(j)) /
                         8;
    }
    return corner_area;
}

}  // namespace

Eigen::VectorXd lumped_masses(const TriangleMesh& mesh, MassType type) {
    detail::require_valid_mesh(mesh, "lumped_masses");
    Eigen::VectorXd masses = Eigen::VectorXd::Zero(mesh.V.rows());
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const detail::Triangle t(mesh, f);
        if (t.degenerate()) {
            continue;
        }
        const Eigen::Vector3d corner = type == MassType::Voronoi
                                           ? voronoi_corner_areas(t)
                                           : Eigen::Vector3d::Constant(t.area() / 3);
        for (int k = 0; k < 3; ++k) {
            masses[mesh.F(f, k)] += corner[k];
        }
    }
    return masses;
}

Eigen::SparseMatrix<double> mass_matrix(const TriangleMesh& mesh, MassType type) {
    if (type != MassType::Full) {
        const Eigen::VectorXd masses = lumped_masses(mesh, type);
        Eigen::SparseMatrix<double> M(masses.size(), masses.size());
        M.reserve(Eigen::VectorXi::Ones(masses.size()));
        for (Eigen::Index i = 0; i < masses.size(); ++i) {
            M.insert(i, i) = masses[i];
        }
        M.makeCompressed();
        return M;
    }
    detail::require_valid_mesh(mesh, "mass_matrix");
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<std::size_t>(9 * mesh.F.rows()));
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        // Zero-area faces add explicit zeros, so the pattern depends only on the connectivity.
        const detail::Triangle t(mesh, f);
        const double area = t.degenerate() ? 0.0 : t.area();
        for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) {
                triplets.emplace_back(mesh.F(f, a), mesh.F(f, b), area / (a == b ? 6 : 12));
            }
        }
    }
    Eigen::SparseMatrix<double> M(mesh.V.rows(), mesh.V.rows());
    M.setFromTriplets(triplets.begin(), triplets.end());
    return M;
}

}  // namespace genflow
