// SPDX-License-Identifier: MIT
// The matrix-free Krylov solvers against dense LU on small systems: converged to the tolerance
// asked, through restarts, with and without a preconditioner.
#include "numerics/krylov.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace genflow {
namespace {

// I·shift + a random matrix scaled to norm ≤ 1: nonsymmetric, eigenvalues in a disc around
// `shift`, so GMRES converges at a known rate.
Eigen::MatrixXd nonsymmetric(int n, double shift, unsigned seed) {
    std::mt19937 generator(seed);
    std::normal_distribution<double> normal;
    Eigen::MatrixXd R(n, n);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            R(i, j) = normal(generator);
        }
    }
    return shift * Eigen::MatrixXd::Identity(n, n) + R / R.operatorNorm();
}

Eigen::VectorXd random_vector(int n, unsigned seed) {
    std::mt19937 generator(seed);
    std::normal_distribution<double> normal;
    Eigen::VectorXd v(n);
    for (int i = 0; i < n; ++i) {
        v[i] = normal(generator);
    }
    return v;
}

detail::LinearOperator product(const Eigen::MatrixXd& M) {
    return [&M](const Eigen::VectorXd& x) -> Eigen::VectorXd { return M * x; };
}

TEST(Gmres, SolvesThroughRestartsToTheToleranceAsked) {
    const int n = 80;
    const Eigen::MatrixXd A = nonsymmetric(n, 2.0, 1);
    const Eigen::VectorXd b = random_vector(n, 2);
    const Eigen::VectorXd exact = A.partialPivLu().solve(b);
    const auto identity = [](const Eigen::VectorXd& x) -> Eigen::VectorXd { return x; };
    for (const int restart : {50, 3}) {
        const auto solved =
            detail::gmres(product(A), identity, b, Eigen::VectorXd::Zero(n), 1e-10, restart, 500);
        ASSERT_TRUE(solved.converged) << "restart " << restart;
        EXPECT_LE((b - A * solved.x).norm(), 1e-10 * b.norm());
        EXPECT_LE(solved.relative_residual, 1e-10);
        EXPECT_LT((solved.x - exact).norm(), 1e-8 * exact.norm());
    }
}

TEST(Gmres, AnExactPreconditionerConvergesInOneIteration) {
    const int n = 40;
    const Eigen::MatrixXd A = nonsymmetric(n, 1.5, 3);
    const Eigen::MatrixXd inverse = A.inverse();
    const Eigen::VectorXd b = random_vector(n, 4);
    const auto solved =
        detail::gmres(product(A), product(inverse), b, Eigen::VectorXd::Zero(n), 1e-10, 20, 100);
    ASSERT_TRUE(solved.converged);
    EXPECT_EQ(solved.iterations, 1);
    EXPECT_LE((b - A * solved.x).norm(), 1e-10 * b.norm());
    // A good start is kept: from the exact solution nothing is left to do.
    const auto from_exact =
        detail::gmres(product(A), product(inverse), b, inverse * b, 1e-10, 20, 100);
    EXPECT_EQ(from_exact.iterations, 0);
}

TEST(Gmres, AZeroRightHandSideGivesZero) {
    const Eigen::MatrixXd A = nonsymmetric(10, 2.0, 5);
    const auto identity = [](const Eigen::VectorXd& x) -> Eigen::VectorXd { return x; };
    const auto solved = detail::gmres(product(A), identity, Eigen::VectorXd::Zero(10),
                                      Eigen::VectorXd::Ones(10), 1e-10, 5, 50);
    EXPECT_TRUE(solved.converged);
    EXPECT_EQ(solved.x, Eigen::VectorXd::Zero(10));
}

TEST(Gmres, ReportsNonConvergence) {
    const Eigen::MatrixXd A = nonsymmetric(60, 1.05, 6);  // eigenvalues near 0: slow
    const auto identity = [](const Eigen::VectorXd& x) -> Eigen::VectorXd { return x; };
    const auto solved = detail::gmres(product(A), identity, random_vector(60, 7),
                                      Eigen::VectorXd::Zero(60), 1e-12, 2, 4);
    EXPECT_FALSE(solved.converged);
    EXPECT_EQ(solved.iterations, 4);
    EXPECT_GT(solved.relative_residual, 1e-12);
}

// The imaged GMRES's C·x is the image of its solution, whether or not it restarts: combined
// from the images of the vectors A was applied to, it must agree with C times the x returned.
TEST(Gmres, GivesTheImageOfItsSolution) {
    const int n = 60;
    const Eigen::MatrixXd A = nonsymmetric(n, 2.0, 10);
    const Eigen::MatrixXd C = nonsymmetric(n, 0.0, 11).topRows(2 * n / 3);  // any shape
    const Eigen::VectorXd b = random_vector(n, 12);
    int applications = 0;
    const detail::ImagingOperator imaging = [&](const Eigen::VectorXd& v, Eigen::MatrixXd& image) {
        ++applications;
        image = C * v;
        return Eigen::VectorXd(A * v);
    };
    for (const int restart : {50, 3}) {
        applications = 0;
        const auto solved = detail::gmres(imaging, b, 1e-10, restart, 500);
        ASSERT_TRUE(solved.converged) << "restart " << restart;
        EXPECT_LE((b - A * solved.x).norm(), 1e-10 * b.norm());
        EXPECT_LT((solved.image - C * solved.x).norm(), 1e-12 * (C * solved.x).norm());
        // One application an iteration, and one a restart for the residual (none at the
        // start from zero).
        const int restarts = (solved.iterations - 1) / restart;
        EXPECT_EQ(applications, solved.iterations + restarts) << "restart " << restart;
    }
}

TEST(ConjugateGradient, SolvesASymmetricPositiveDefiniteSystem) {
    const int n = 60;
    const Eigen::MatrixXd R = nonsymmetric(n, 0.0, 8);
    const Eigen::MatrixXd A = R * R.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd b = random_vector(n, 9);
    const auto solved =
        detail::conjugate_gradient(product(A), b, Eigen::VectorXd::Zero(n), 1e-10, 500);
    ASSERT_TRUE(solved.converged);
    EXPECT_LE((b - A * solved.x).norm(), 1e-9 * b.norm());
    EXPECT_LT((solved.x - A.llt().solve(b)).norm(), 1e-8 * solved.x.norm());
}

}  // namespace
}  // namespace genflow
