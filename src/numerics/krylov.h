// SPDX-License-Identifier: MIT
// Matrix-free Krylov solvers for the operators that are never formed (the volume-controlled
// metric's B and its implicit system, docs/formulas.md §4).
#pragma once

#include <Eigen/Core>
#include <functional>

namespace genflow::detail {

using LinearOperator = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

struct KrylovResult {
    Eigen::VectorXd x;
    int iterations = 0;
    double relative_residual = 0;
    bool converged = false;
};

/// A linear operator A that also gives a second linear image C·v (`image`, of any shape) of
/// every vector v it is applied to.
using ImagingOperator =
    std::function<Eigen::VectorXd(const Eigen::VectorXd& v, Eigen::MatrixXd& image)>;

struct ImagedKrylovResult : KrylovResult {
    Eigen::MatrixXd image;  // C·x
};

/// Conjugate gradients for A x = b with A symmetric positive definite, from x0.
KrylovResult conjugate_gradient(const LinearOperator& A, const Eigen::VectorXd& b,
                                const Eigen::VectorXd& x0, double tolerance, int max_iterations);

/// Restarted GMRES(restart) for A x = b with right preconditioning by P ≈ A⁻¹, from x0.
/// Converged when ‖b − A x‖ ≤ tolerance·‖b‖.
KrylovResult gmres(const LinearOperator& A, const LinearOperator& P, const Eigen::VectorXd& b,
                   const Eigen::VectorXd& x0, double tolerance, int restart, int max_iterations);

/// GMRES(restart) for A x = b from x = 0, unpreconditioned, with C·x besides: combined from the
/// images of the vectors A was applied to as x is from those vectors, so that C·x costs no
/// further application of C (where C is the costly part of A).
ImagedKrylovResult gmres(const ImagingOperator& A, const Eigen::VectorXd& b, double tolerance,
                         int restart, int max_iterations);

}  // namespace genflow::detail
