// SPDX-License-Identifier: MIT
#include "matching/functional_operators.h"

#include <Eigen/Geometry>

#include "operators/triangle.h"

namespace genflow::detail {

Eigen::MatrixXd multiplication_operator(const Eigen::MatrixXd& functions,
                                        const Eigen::VectorXd& masses, const Eigen::VectorXd& f) {
    return functions.transpose() * (masses.array() * f.array()).matrix().asDiagonal() * functions;
}

namespace {

// The gradient of `f` (piecewise linear) on a face with corners x and twice-area normal
// `cross`: Σ_a f_a n × e_a/(2A), e_a the edge opposite corner a, counter-clockwise.
Eigen::Vector3d face_gradient(const Triangle& triangle, const Eigen::Vector3d& corner_values) {
    const Eigen::Vector3d n = triangle.cross / triangle.double_area;
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
    for (int a = 0; a < 3; ++a) {
        const Eigen::Vector3d edge = triangle.x[(a + 2) % 3] - triangle.x[(a + 1) % 3];
        gradient += corner_values(a) * n.cross(edge) / triangle.double_area;
    }
    return gradient;
}

Eigen::Vector3d corner_values(const TriangleMesh& mesh, Eigen::Index t, const Eigen::VectorXd& f) {
    return {f(mesh.F(t, 0)), f(mesh.F(t, 1)), f(mesh.F(t, 2))};
}

}  // namespace

Eigen::MatrixXd orientation_operator(const TriangleMesh& mesh, const Eigen::MatrixXd& functions,
                                     const Eigen::VectorXd& f) {
    // Per face t: the row of corner means (Σ_u φ(u))/3 times A_t, and the directional
    // derivatives Σ_v φ(v) ∇f·e_v/(2 A_t), so entry (i, j) gathers
    // Σ_t (Σ_u φ_i(u)) (Σ_v φ_j(v) ∇f·e_v) / 6.
    const Eigen::Index k = functions.cols();
    Eigen::MatrixXd sums(mesh.F.rows(), k);
    Eigen::MatrixXd derivatives(mesh.F.rows(), k);
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) {
        const Triangle triangle(mesh, t);
        sums.row(t).setZero();
        derivatives.row(t).setZero();
        if (!(triangle.double_area > 0)) {
            continue;
        }
        const Eigen::Vector3d gradient = face_gradient(triangle, corner_values(mesh, t, f));
        for (int a = 0; a < 3; ++a) {
            const Eigen::Vector3d edge = triangle.x[(a + 2) % 3] - triangle.x[(a + 1) % 3];
            const auto row = functions.row(mesh.F(t, a));
            sums.row(t) += row;
            derivatives.row(t) += gradient.dot(edge) * row;
        }
    }
    const Eigen::MatrixXd op = sums.transpose() * derivatives / 6;
    return 0.5 * (op - op.transpose());
}

Eigen::VectorXd signed_descriptor(const TriangleMesh& mesh, const Eigen::MatrixXd& functions,
                                  const Eigen::VectorXd& masses, const Eigen::VectorXd& f,
                                  const Eigen::VectorXd& g) {
    Eigen::VectorXd spread = Eigen::VectorXd::Zero(mesh.V.rows());
    Eigen::VectorXd weight = Eigen::VectorXd::Zero(mesh.V.rows());
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) {
        const Triangle triangle(mesh, t);
        if (!(triangle.double_area > 0)) {
            continue;
        }
        const Eigen::Vector3d n = triangle.cross / triangle.double_area;
        const double value = n.dot(face_gradient(triangle, corner_values(mesh, t, f))
                                       .cross(face_gradient(triangle, corner_values(mesh, t, g))));
        for (int a = 0; a < 3; ++a) {
            spread(mesh.F(t, a)) += triangle.double_area * value;
            weight(mesh.F(t, a)) += triangle.double_area;
        }
    }
    const Eigen::VectorXd mean =
        (weight.array() > 0).select(spread.array() / weight.array(), 0).matrix();
    return functions * (functions.transpose() * masses.asDiagonal() * mean);
}

}  // namespace genflow::detail
