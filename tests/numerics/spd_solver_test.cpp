// SPDX-License-Identifier: MIT
// The sparse SPD solver facade on the H1 matrix M + K of a sphere, on both sides of the size
// where it changes factorization (simplicial below 60,000 rows, CHOLMOD's choice above).
#include "numerics/spd_solver.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <array>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// The 7-point Laplacian of a k×k×k grid plus the identity: a factor far denser in flops per
// entry than a surface mesh's (nested fill in three dimensions).
Eigen::SparseMatrix<double> grid_laplacian(int k) {
    const auto index = [k](int x, int y, int z) { return (z * k + y) * k + x; };
    std::vector<Eigen::Triplet<double>> entries;
    for (int z = 0; z < k; ++z) {
        for (int y = 0; y < k; ++y) {
            for (int x = 0; x < k; ++x) {
                const int i = index(x, y, z);
                entries.emplace_back(i, i, 7.0);
                for (const auto& [dx, dy, dz] :
                     {std::array{1, 0, 0}, std::array{0, 1, 0}, std::array{0, 0, 1}}) {
                    if (x + dx < k && y + dy < k && z + dz < k) {
                        const int j = index(x + dx, y + dy, z + dz);
                        entries.emplace_back(i, j, -1.0);
                        entries.emplace_back(j, i, -1.0);
                    }
                }
            }
        }
    }
    Eigen::SparseMatrix<double> A(k * k * k, k * k * k);
    A.setFromTriplets(entries.begin(), entries.end());
    return A;
}

void expect_solves(const Eigen::SparseMatrix<double>& A,
                   Factorization factorization = Factorization::BySize) {
    detail::SpdSolver solver(factorization);
    solver.compute(A, "test");
    const Eigen::MatrixXd X_true = test::random_matrix(A.rows(), 3, 1);
    const Eigen::MatrixXd B = A * X_true;
    Eigen::MatrixXd X = solver.solve(B);
    EXPECT_LT((X - X_true).norm(), 1e-8 * X_true.norm()) << A.rows();
    // A new matrix of the same pattern is factored without a new symbolic analysis.
    const Eigen::SparseMatrix<double> twice = 2 * A;
    solver.compute(twice, "test");
    X = solver.solve(B);
    EXPECT_LT((2 * X - X_true).norm(), 1e-8 * X_true.norm()) << A.rows();
    EXPECT_EQ(solver.analyses(), 1);
    // An indefinite one is refused.
    Eigen::SparseMatrix<double> indefinite = A;
    indefinite.coeffRef(A.rows() / 2, A.rows() / 2) = -1;
    EXPECT_THROW(solver.compute(indefinite, "test"), SolverError);
    EXPECT_THROW((void)solver.solve(B.topRows(10)), InvalidInput);
}

TEST(SpdSolver, SolvesSmallAndLargeSystemsAndRefusesIndefiniteOnes) {
    expect_solves(test::sphere_h1_matrix(3, 1));  // 642 rows
    expect_solves(test::sphere_h1_matrix(6, 2));  // 81,924 rows
    expect_solves(test::sphere_h1_matrix(3, 1), Factorization::Supernodal);
    expect_solves(test::sphere_h1_matrix(5, 1), Factorization::Supernodal);  // 10,242 rows
}

// ByFlopDensity factors a sparse-filling matrix (37 flops per entry of the factor) simplicially
// and a dense-filling one supernodally, and solves both.
TEST(SpdSolver, ChoosesTheFactorizationByFlopDensity) {
    const Eigen::SparseMatrix<double> surface = test::sphere_h1_matrix(3, 1);
    const Eigen::SparseMatrix<double> volume = grid_laplacian(24);
    expect_solves(surface, Factorization::ByFlopDensity);
    expect_solves(volume, Factorization::ByFlopDensity);
    detail::SpdSolver solver(Factorization::ByFlopDensity);
    solver.compute(surface, "test");
    EXPECT_FALSE(solver.supernodal());
    solver.compute(volume, "test");
    EXPECT_EQ(solver.supernodal(), std::string(detail::SpdSolver::backend()) == "CHOLMOD");
    detail::SpdSolver supernodal(Factorization::Supernodal);
    supernodal.compute(surface, "test");
    EXPECT_EQ(supernodal.supernodal(), std::string(detail::SpdSolver::backend()) == "CHOLMOD");
}

// The two factorizations of the same matrix agree to rounding.
TEST(SpdSolver, SupernodalAndSimplicialAgree) {
    const Eigen::SparseMatrix<double> A = test::sphere_h1_matrix(5, 1);
    const Eigen::MatrixXd B = test::random_matrix(A.rows(), 3, 3);
    detail::SpdSolver simplicial(Factorization::BySize);
    detail::SpdSolver supernodal(Factorization::Supernodal);
    simplicial.compute(A, "test");
    supernodal.compute(A, "test");
    const Eigen::MatrixXd X = simplicial.solve(B);
    EXPECT_LT((supernodal.solve(B) - X).norm(), 1e-10 * X.norm());
}

// A supernodal factor solves one to four columns by its own walk over the factor, and more
// through CHOLMOD: every count solves, each column as it is solved alone, and both paths
// agree. The grid Laplacian's supernodes are wide (many columns each), the sphere's narrow.
TEST(SpdSolver, SolvesAnyNumberOfColumnsWithASupernodalFactor) {
    const bool cholmod = std::string(detail::SpdSolver::backend()) == "CHOLMOD";
    for (const Eigen::SparseMatrix<double>& A :
         {test::sphere_h1_matrix(5, 1), grid_laplacian(20)}) {
        detail::SpdSolver solver(Factorization::Supernodal);
        solver.compute(A, "test");
        EXPECT_EQ(solver.supernodal(), cholmod);
        const Eigen::MatrixXd B = test::random_matrix(A.rows(), 6, 4);
        const Eigen::MatrixXd all = solver.solve(B);  // six columns: CHOLMOD's solve
        EXPECT_LT((A * all - B).norm(), 1e-12 * B.norm()) << A.rows();
        for (Eigen::Index columns = 1; columns <= 5; ++columns) {
            const Eigen::MatrixXd X = solver.solve(B.leftCols(columns));
            EXPECT_LT((X - all.leftCols(columns)).norm(), 1e-13 * all.leftCols(columns).norm())
                << A.rows() << " rows, " << columns << " columns";
            for (Eigen::Index c = 0; c < columns && columns <= 4 && cholmod; ++c) {
                const Eigen::MatrixXd alone = solver.solve(B.col(c));
                EXPECT_EQ(X.col(c), alone.col(0)) << columns << " columns, column " << c;
            }
        }
    }
}

// ByFlopDensity factors a matrix that splits in two halves (SplitCholesky), the other modes
// whole; both solve.
TEST(SpdSolver, FactorsInTwoHalvesByFlopDensity) {
    const Eigen::SparseMatrix<double> A = test::sphere_h1_matrix(6, 1);  // 40,962 rows
    expect_solves(A, Factorization::ByFlopDensity);
    detail::SpdSolver by_density(Factorization::ByFlopDensity);
    detail::SpdSolver supernodal(Factorization::Supernodal);
    by_density.compute(A, "test");
    supernodal.compute(A, "test");
    EXPECT_EQ(by_density.split(), std::string(detail::SpdSolver::backend()) == "CHOLMOD");
    EXPECT_FALSE(supernodal.split());
    const Eigen::MatrixXd B = test::random_matrix(A.rows(), 3, 8);
    const Eigen::MatrixXd X = supernodal.solve(B);
    EXPECT_LT((by_density.solve(B) - X).norm(), 1e-12 * X.norm());
}

// A factor in two halves whose solves before the next factorization do less arithmetic than
// the factorization (a flow's step, one solve; a volume-controlled step, six) is analysed again
// with wider supernodes at its second factorization; one solved far more (a frozen metric) is
// not. All solve, and none needs another separator.
TEST(SpdSolver, WidensTheSupernodesOfAFactorWhoseSolvesCostLessThanItsFactorization) {
    const bool cholmod = std::string(detail::SpdSolver::backend()) == "CHOLMOD";
    const Eigen::SparseMatrix<double> A = test::sphere_h1_matrix(5, 1);  // 143 flops an entry
    const Eigen::MatrixXd B = test::random_matrix(A.rows(), 3, 11);
    struct Use {
        int solves;
        bool widened;
    };
    for (const Use use : {Use{1, true}, Use{6, true}, Use{100, false}}) {
        detail::SpdSolver solver(Factorization::ByFlopDensity);
        for (int step = 1; step <= 3; ++step) {
            const Eigen::SparseMatrix<double> scaled = step * A;
            solver.compute(scaled, "test");
            for (int k = 0; k < use.solves; ++k) {
                ASSERT_LT((scaled * solver.solve(B) - B).norm(), 1e-12 * B.norm())
                    << use.solves << " solves, step " << step;
            }
            EXPECT_EQ(solver.wide_supernodes(), cholmod && use.widened && step > 1)
                << use.solves << " solves, step " << step;
        }
        EXPECT_EQ(solver.analyses(), 1);
    }
}

// ByFlopDensityWide gives supernodal halves their wider supernodes from the first analysis,
// whatever the solves; simplicial halves have none. Both solve as ByFlopDensity's factors do,
// with one analysis.
TEST(SpdSolver, WidensTheSupernodesFromTheFirstAnalysisWhenAskedTo) {
    const bool cholmod = std::string(detail::SpdSolver::backend()) == "CHOLMOD";
    struct Case {
        Eigen::SparseMatrix<double> A;
        bool widened;
    };
    for (const Case& c : {Case{test::sphere_h1_matrix(5, 1), true},      // 143 flops an entry
                          Case{test::sphere_h1_matrix(4, 1), false}}) {  // simplicial halves
        const Eigen::MatrixXd B = test::random_matrix(c.A.rows(), 3, 14);
        detail::SpdSolver narrow(Factorization::ByFlopDensity);
        detail::SpdSolver wide(Factorization::ByFlopDensityWide);
        narrow.compute(c.A, "test");
        wide.compute(c.A, "test");
        EXPECT_EQ(wide.wide_supernodes(), cholmod && c.widened) << c.A.rows();
        for (int step = 1; step <= 2; ++step) {
            wide.compute(c.A, "test");
            EXPECT_LT((wide.solve(B) - narrow.solve(B)).norm(), 1e-12 * narrow.solve(B).norm());
        }
        EXPECT_EQ(wide.analyses(), 1);
    }
}

// A task given to compute() runs once, alongside the factorization in two halves or after a
// whole one, and what it throws comes out of compute().
TEST(SpdSolver, RunsATaskAlongsideTheFactorization) {
    for (const Factorization factorization :
         {Factorization::BySize, Factorization::ByFlopDensity, Factorization::ByFlopDensityWide}) {
        const Eigen::SparseMatrix<double> A = test::sphere_h1_matrix(4, 1);
        detail::SpdSolver solver(factorization);
        int runs = 0;
        solver.compute(A, "test", [&runs] { ++runs; });
        EXPECT_EQ(runs, 1);
        const Eigen::MatrixXd B = test::random_matrix(A.rows(), 3, 15);
        EXPECT_LT((A * solver.solve(B) - B).norm(), 1e-12 * B.norm());
        EXPECT_THROW(solver.compute(A, "test", [] { throw InvalidInput("task"); }), InvalidInput);
    }
}

// Called at the top level, the factorization holds CHOLMOD's own thread teams to one thread;
// inside a parallel region (a matcher's flows side by side) it runs as it is: the same bits.
TEST(SpdSolver, FactorsToTheSameBitsInsideAndOutsideAParallelRegion) {
    const Eigen::SparseMatrix<double> A = test::sphere_h1_matrix(6, 2);  // supernodal: 81,924 rows
    const Eigen::MatrixXd B = test::random_matrix(A.rows(), 3, 2);
    detail::SpdSolver top;
    top.compute(A, "test");
    const Eigen::MatrixXd at_top = top.solve(B);
    Eigen::MatrixXd inside;
#pragma omp parallel num_threads(2)
    {
#pragma omp single
        {
            detail::SpdSolver nested;
            nested.compute(A, "test");
            inside = nested.solve(B);
        }
    }
    EXPECT_EQ(at_top, inside);
    EXPECT_LT((A * at_top - B).norm(), 1e-8 * B.norm());
}

}  // namespace
}  // namespace genflow
