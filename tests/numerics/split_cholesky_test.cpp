// SPDX-License-Identifier: MIT
// The factorization in two halves: it solves as the whole factor does, column by column to the
// same bits, with or without a separator, and refuses a matrix that is not positive definite
// even where both halves are.
#include "numerics/split_cholesky.h"

#ifdef GENFLOW_HAS_CHOLMOD

#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <vector>

#include "genflow/exceptions.h"
#include "numerics/spd_solver.h"
#include "support/test_meshes.h"

extern "C" {
int openblas_get_num_threads() __attribute__((weak));
}

namespace genflow {
namespace {

// The second-difference matrix of a path of n vertices, `diagonal` on its diagonal.
Eigen::SparseMatrix<double> path_matrix(int n, double diagonal) {
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < n; ++i) {
        entries.emplace_back(i, i, diagonal);
        if (i + 1 < n) {
            entries.emplace_back(i, i + 1, -1.0);
            entries.emplace_back(i + 1, i, -1.0);
        }
    }
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(entries.begin(), entries.end());
    return A;
}

// Flop densities at which both halves' factors are supernodal, and simplicial: each kind reads
// its matrix in a triangle of its own.
constexpr double kAlwaysSupernodal = 0;
constexpr double kNeverSupernodal = 1e300;

void expect_solves_as_the_whole_factor(const Eigen::SparseMatrix<double>& A,
                                       double supernodal_switch) {
    detail::SplitCholesky split;
    ASSERT_TRUE(split.analyze(A, supernodal_switch));
    ASSERT_TRUE(split.factorize(A));
    EXPECT_EQ(split.supernodal(), supernodal_switch == kAlwaysSupernodal);
    detail::SpdSolver whole(Factorization::Supernodal);
    whole.compute(A, "test");
    const Eigen::MatrixXd B = test::random_matrix(A.rows(), 6, 5);
    const Eigen::MatrixXd X = split.solve(B);
    EXPECT_LT((A * X - B).norm(), 1e-12 * B.norm()) << A.rows();
    EXPECT_LT((X - whole.solve(B)).norm(), 1e-12 * X.norm()) << A.rows();
    for (Eigen::Index c = 0; c < B.cols(); ++c) {
        EXPECT_EQ(split.solve(B.col(c)).col(0), X.col(c)) << "column " << c;
    }
}

TEST(SplitCholesky, SolvesAsTheWholeFactorDoes) {
    const Eigen::SparseMatrix<double> sphere = test::sphere_h1_matrix(5);  // 10,242 rows
    detail::SplitCholesky split;
    ASSERT_TRUE(split.analyze(sphere, 80));
    EXPECT_GT(split.separator().size(), 10U);  // a cut around the sphere
    EXPECT_LT(split.separator().size(), 0.05 * static_cast<double>(sphere.rows()));
    for (const double supernodal_switch : {kAlwaysSupernodal, kNeverSupernodal}) {
        expect_solves_as_the_whole_factor(sphere, supernodal_switch);
        // No separator: two spheres.
        expect_solves_as_the_whole_factor(test::sphere_h1_matrix(4, 2), supernodal_switch);
        expect_solves_as_the_whole_factor(path_matrix(5000, 2.5), supernodal_switch);
    }
}

// A new matrix of the analysed pattern factors without a new analysis; so does a matrix of
// another scale.
TEST(SplitCholesky, RefactorsAMatrixOfTheSamePattern) {
    const Eigen::SparseMatrix<double> A = test::sphere_h1_matrix(4);
    detail::SplitCholesky split;
    ASSERT_TRUE(split.analyze(A, 80));
    const Eigen::MatrixXd B = test::random_matrix(A.rows(), 3, 6);
    ASSERT_TRUE(split.factorize(A));
    const Eigen::MatrixXd X = split.solve(B);
    const Eigen::SparseMatrix<double> twice = 2 * A;
    ASSERT_TRUE(split.factorize(twice));
    EXPECT_LT((2 * split.solve(B) - X).norm(), 1e-12 * X.norm());
}

// Wider supernodes change how the factor is stored, not what it solves.
TEST(SplitCholesky, SolvesAsBeforeWithWiderSupernodes) {
    const Eigen::SparseMatrix<double> A = test::sphere_h1_matrix(5);
    const Eigen::MatrixXd B = test::random_matrix(A.rows(), 3, 12);
    detail::SplitCholesky split;
    ASSERT_TRUE(split.analyze(A, 80));
    ASSERT_TRUE(split.factorize(A));
    const Eigen::MatrixXd narrow = split.solve(B);
    ASSERT_TRUE(split.widen_supernodes());
    ASSERT_TRUE(split.factorize(A));
    const Eigen::MatrixXd wide = split.solve(B);
    EXPECT_LT((A * wide - B).norm(), 1e-12 * B.norm());
    EXPECT_LT((wide - narrow).norm(), 1e-12 * narrow.norm());
}

// A task given to the factorization runs once, on the thread of one half, and changes nothing
// of the factor; what it throws comes out of factorize(), and the next factorization works.
TEST(SplitCholesky, RunsATaskAlongsideItsHalvesAndPassesOnWhatItThrows) {
    const Eigen::SparseMatrix<double> A = test::sphere_h1_matrix(5);
    const Eigen::MatrixXd B = test::random_matrix(A.rows(), 3, 13);
    for (const double supernodal_switch : {kAlwaysSupernodal, kNeverSupernodal}) {
        detail::SplitCholesky split;
        ASSERT_TRUE(split.analyze(A, supernodal_switch));
        ASSERT_TRUE(split.factorize(A));
        const Eigen::MatrixXd alone = split.solve(B);
        int runs = 0;
        ASSERT_TRUE(split.factorize(A, [&runs] { ++runs; }));
        EXPECT_EQ(runs, 1);
        EXPECT_EQ(split.solve(B), alone) << "supernodal switch " << supernodal_switch;
        EXPECT_THROW((void)split.factorize(A, [] { throw InvalidInput("task"); }), InvalidInput);
        ASSERT_TRUE(split.factorize(A));
        EXPECT_EQ(split.solve(B), alone) << "supernodal switch " << supernodal_switch;
    }
}

// On a path, with d on the diagonal at the separator and 2 elsewhere, each half's Schur
// complement on the separator is d − (1 − 1/(k+1)) and the whole's d − 2(1 − 1/(k+1)) for halves
// of k vertices: at d = 1.5 both halves are positive definite and A is not.
TEST(SplitCholesky, RefusesAMatrixThatIsNotPositiveDefiniteWhereItsHalvesAre) {
    Eigen::SparseMatrix<double> A = path_matrix(2001, 2.0);
    detail::SplitCholesky split;
    ASSERT_TRUE(split.analyze(A, 80));
    ASSERT_EQ(split.separator().size(), 1U);
    const int cut = split.separator().front();
    ASSERT_GT(cut, 10);
    ASSERT_LT(cut, 1990);
    EXPECT_TRUE(split.factorize(A));
    A.coeffRef(cut, cut) = 1.5;
    EXPECT_FALSE(split.factorize(A));
    A.coeffRef(cut, cut) = 2.0;
    A.coeffRef(cut / 2, cut / 2) = -1.0;  // inside a half
    EXPECT_FALSE(split.factorize(A));
}

// A dense matrix has no small separator: the split declines it, and SpdSolver factors it whole.
TEST(SplitCholesky, DeclinesAMatrixWithoutASmallSeparator) {
    const Eigen::MatrixXd M = test::random_matrix(120, 120, 9);
    const Eigen::MatrixXd dense = M.transpose() * M + 120 * Eigen::MatrixXd::Identity(120, 120);
    const Eigen::SparseMatrix<double> A = dense.sparseView();
    detail::SplitCholesky split;
    EXPECT_FALSE(split.analyze(A, 80));
    detail::SpdSolver solver(Factorization::ByFlopDensity);
    solver.compute(A, "test");
    EXPECT_FALSE(solver.split());
    const Eigen::MatrixXd B = test::random_matrix(120, 2, 10);
    EXPECT_LT((dense * solver.solve(B) - B).norm(), 1e-12 * B.norm());
}

// The halves run side by side on two threads (the BLAS held to one meanwhile, and given back its
// own count after; supernodal halves on threads of their own), or one after the other inside a
// parallel region: the same bits, for either kind of factor.
TEST(SplitCholesky, FactorsToTheSameBitsOnOneThreadOrTwo) {
    const Eigen::SparseMatrix<double> A = test::sphere_h1_matrix(5);
    const Eigen::MatrixXd B = test::random_matrix(A.rows(), 3, 7);
    const int blas_threads = openblas_get_num_threads != nullptr ? openblas_get_num_threads() : 0;
    for (const double supernodal_switch : {kAlwaysSupernodal, kNeverSupernodal}) {
        detail::SplitCholesky top;
        ASSERT_TRUE(top.analyze(A, supernodal_switch));
        ASSERT_TRUE(top.factorize(A));
        EXPECT_EQ(top.supernodal(), supernodal_switch == kAlwaysSupernodal);
        const Eigen::MatrixXd at_top = top.solve(B);
        EXPECT_EQ(openblas_get_num_threads != nullptr ? openblas_get_num_threads() : 0,
                  blas_threads);
        Eigen::MatrixXd inside;
#pragma omp parallel num_threads(2)
        {
#pragma omp single
            {
                detail::SplitCholesky nested;
                if (nested.analyze(A, supernodal_switch) && nested.factorize(A)) {
                    inside = nested.solve(B);
                }
            }
        }
        EXPECT_EQ(at_top, inside) << "supernodal switch " << supernodal_switch;
    }
}

}  // namespace
}  // namespace genflow

#endif
