// SPDX-License-Identifier: MIT
// The anchor of `genflow smooth --method fairing`: libigl's implicit fairing loop (its tutorial
// 205), re-expressed with Eigen alone so that it builds from Debian's packages. The cotangent
// matrix L (negative semidefinite, ½(cot α + cot β) off the diagonal) and the barycentric mass
// matrix M (a third of each face's area per corner) are assembled from triplets as libigl's
// cotmatrix() and massmatrix() assemble them; each step factors S = M − dt·L with a fresh
// SimplicialLLT (ordering, symbolic analysis and numeric factorization, as the tutorial
// constructs it in its loop) and sets U ← S⁻¹·M·U. dt is in units of h², h the input's mean edge
// length, as genflow smooth's --dt, so that both take the same steps: genflow's H1 step with
// λ = dt is this one (docs/formulas.md).
//
// Usage: fairing_anchor MESH STEPS OUT [--dt D] [--rebuild]
//   --rebuild: L and M of the current U at every step (else once, from the input, as the
//              tutorial does for L).
// The mesh is read and the result written (OUT) by genflow's reader and writer, which both sides
// then share: what is compared is the set-up and the steps. Prints the area after the last step
// (to check both did the same work).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "genflow/io/read_mesh.h"
#include "genflow/io/write_mesh.h"

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Half the cotangent of the angle at corner c of face f, as libigl's cotmatrix_entries().
double half_cotangent(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, Eigen::Index f, int c) {
    const Eigen::Vector3d a = V.row(F(f, c)).transpose();
    const Eigen::Vector3d u = V.row(F(f, (c + 1) % 3)).transpose() - a;
    const Eigen::Vector3d v = V.row(F(f, (c + 2) % 3)).transpose() - a;
    return 0.5 * u.dot(v) / u.cross(v).norm();
}

SparseMatrix cotmatrix(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(12 * F.rows()));
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            const int i = F(f, (c + 1) % 3);
            const int j = F(f, (c + 2) % 3);
            const double w = half_cotangent(V, F, f, c);
            entries.emplace_back(i, j, w);
            entries.emplace_back(j, i, w);
            entries.emplace_back(i, i, -w);
            entries.emplace_back(j, j, -w);
        }
    }
    SparseMatrix L(V.rows(), V.rows());
    L.setFromTriplets(entries.begin(), entries.end());
    return L;
}

SparseMatrix barycentric_massmatrix(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(3 * F.rows()));
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        const Eigen::Vector3d a = V.row(F(f, 0)).transpose();
        const double third =
            (V.row(F(f, 1)).transpose() - a).cross(V.row(F(f, 2)).transpose() - a).norm() / 6;
        for (int c = 0; c < 3; ++c) {
            entries.emplace_back(F(f, c), F(f, c), third);
        }
    }
    SparseMatrix M(V.rows(), V.rows());
    M.setFromTriplets(entries.begin(), entries.end());
    return M;
}

double mean_edge_length(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
    double sum = 0;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            sum += (V.row(F(f, c)) - V.row(F(f, (c + 1) % 3))).norm();
        }
    }
    return sum / static_cast<double>(3 * F.rows());
}

double area(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
    return barycentric_massmatrix(V, F).sum();  // a third of each face at each corner
}

int run(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: fairing_anchor MESH STEPS OUT [--dt D] [--rebuild]\n");
        return 2;
    }
    const genflow::TriangleMesh mesh = genflow::read_mesh(argv[1]);
    const int steps = std::atoi(argv[2]);
    double dt_in_h2 = 0.5;
    bool rebuild = false;
    for (int a = 4; a < argc; ++a) {
        const std::string arg = argv[a];
        if (arg == "--rebuild") {
            rebuild = true;
        } else if (arg == "--dt" && a + 1 < argc) {
            dt_in_h2 = std::atof(argv[++a]);
        }
    }
    const Eigen::MatrixX3i& F = mesh.F;
    Eigen::MatrixX3d U = mesh.V;
    const double h = mean_edge_length(U, F);
    const double dt = dt_in_h2 * h * h;
    SparseMatrix L = cotmatrix(U, F);
    SparseMatrix M = barycentric_massmatrix(U, F);
    for (int step = 0; step < steps; ++step) {
        if (rebuild && step > 0) {
            L = cotmatrix(U, F);
            M = barycentric_massmatrix(U, F);
        }
        const SparseMatrix S = M - dt * L;
        const Eigen::SimplicialLLT<SparseMatrix> solver(S);
        if (solver.info() != Eigen::Success) {
            std::fprintf(stderr, "fairing_anchor: factorization failed at step %d\n", step + 1);
            return 1;
        }
        U = solver.solve(M * U).eval();
    }
    genflow::write_mesh(argv[3], genflow::TriangleMesh{U, F});
    std::printf("fairing_anchor: %d steps, area %.9g\n", steps, area(U, F));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "fairing_anchor: %s\n", error.what());
        return 2;
    }
}
