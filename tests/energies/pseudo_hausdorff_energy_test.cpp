// SPDX-License-Identifier: MIT
#include "genflow/energies/pseudo_hausdorff_energy.h"

#include <gtest/gtest.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "genflow/exceptions.h"
#include "genflow/flows/implicit_euler.h"
#include "genflow/mesh/primitives.h"
#include "genflow/metrics/l2_metric.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"
#include "support/reference_distances.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

struct Pair {
    TriangleMesh X;
    TriangleMesh Y;
};

// A small irregular source and a differently sampled, shifted and stretched target.
Pair small_pair() {
    TriangleMesh Y = test::noisy_icosphere(2, 0.15, 7);
    Y.V = Y.V * Eigen::Vector3d(1.1, 1.0, 0.95).asDiagonal();
    Y.V.rowwise() += Eigen::RowVector3d(0.15, 0.0, -0.05);
    return {test::noisy_icosphere(1, 0.2, 3), Y};
}

PseudoHausdorffEvaluation evaluate(const Pair& pair, const PseudoHausdorffOptions& options) {
    return pseudo_hausdorff(pair.X.V, lumped_masses(pair.X, MassType::Barycentric), pair.Y.V,
                            lumped_masses(pair.Y, MassType::Barycentric), options);
}

// Brute-force Hausdorff distance between the vertex sets.
using test::vertex_hausdorff;

TEST(PseudoHausdorff, DifferentialMatchesFiniteDifferencesForSeveralAlphaAndEpsilon) {
    const Pair pair = small_pair();
    const Eigen::VectorXd mx = lumped_masses(pair.X, MassType::Barycentric);
    const Eigen::VectorXd my = lumped_masses(pair.Y, MassType::Barycentric);
    for (const auto& [alpha, epsilon] :
         {std::pair{1.0, 0.05}, {4.0, 0.05}, {10.0, 0.02}, {20.0, 0.01}, {7.5, 0.03}}) {
        for (const double truncation : {0.0, 1e-12}) {
            const PseudoHausdorffOptions options{
                .alpha = alpha, .epsilon = epsilon, .truncation = truncation};
            const auto value = [&](const TriangleMesh& m) {
                return pseudo_hausdorff(m.V, mx, pair.Y.V, my, options).value;
            };
            const VertexField fd = test::finite_difference_gradient(value, pair.X, 1e-6);
            const VertexField analytic =
                pseudo_hausdorff(pair.X.V, mx, pair.Y.V, my, options).differential;
            EXPECT_LT(test::relative_error(analytic, fd), 1e-6)
                << "alpha " << alpha << " truncation " << truncation;
        }
    }
}

// S = λ Σ_i a_i/f_i + Σ_j b_j/g_j written out in long double, without descriptors.
double weighed_reference(const Pair& pair, double alpha, double epsilon, double coverage) {
    const Eigen::VectorXd mx = lumped_masses(pair.X, MassType::Barycentric);
    const Eigen::VectorXd my = lumped_masses(pair.Y, MassType::Barycentric);
    const auto P = static_cast<double>(pair.X.V.rows());
    const auto Q = static_cast<double>(pair.Y.V.rows());
    std::vector<long double> f(pair.X.V.rows(), 0);
    std::vector<long double> g(pair.Y.V.rows(), 0);
    for (Eigen::Index i = 0; i < pair.X.V.rows(); ++i) {
        for (Eigen::Index j = 0; j < pair.Y.V.rows(); ++j) {
            const long double d =
                (pair.X.V.row(i) - pair.Y.V.row(j)).squaredNorm() + epsilon * epsilon;
            const long double power = std::pow(d, -static_cast<long double>(alpha));
            f[static_cast<std::size_t>(i)] += my[j] / Q * power;
            g[static_cast<std::size_t>(j)] += mx[i] / P * power;
        }
    }
    long double S = 0;
    for (Eigen::Index i = 0; i < pair.X.V.rows(); ++i) {
        S += coverage * mx[i] / P / f[static_cast<std::size_t>(i)];
    }
    for (Eigen::Index j = 0; j < pair.Y.V.rows(); ++j) {
        S += my[j] / Q / g[static_cast<std::size_t>(j)];
    }
    return static_cast<double>(std::pow(S, 1 / (2 * static_cast<long double>(alpha))) - epsilon);
}

// The moving set's coverage term weighed by λ: the value is the written-out sums', the
// differential the finite differences', and at λ = 0 a moving point far from the fixed set
// feels no pull (only the fixed points need a counterpart).
TEST(PseudoHausdorff, WeighsTheMovingSetsCoverageTerm) {
    Pair pair = small_pair();
    pair.X.V.row(0) *= 3;  // a moving point with no counterpart
    const Eigen::VectorXd mx = lumped_masses(pair.X, MassType::Barycentric);
    const Eigen::VectorXd my = lumped_masses(pair.Y, MassType::Barycentric);
    for (const double coverage : {0.0, 0.3, 1.0}) {
        const PseudoHausdorffOptions options{
            .alpha = 6, .epsilon = 0.04, .truncation = 0, .moving_coverage = coverage};
        const auto value = [&](const TriangleMesh& m) {
            return pseudo_hausdorff(m.V, mx, pair.Y.V, my, options).value;
        };
        const PseudoHausdorffEvaluation evaluation =
            pseudo_hausdorff(pair.X.V, mx, pair.Y.V, my, options);
        EXPECT_NEAR(evaluation.value, weighed_reference(pair, 6, 0.04, coverage), 1e-12)
            << coverage;
        EXPECT_LT(test::relative_error(evaluation.differential,
                                       test::finite_difference_gradient(value, pair.X, 1e-6)),
                  1e-6)
            << coverage;
        const double pull = evaluation.differential.row(0).norm() /
                            evaluation.differential.rowwise().norm().maxCoeff();
        if (coverage == 0) {
            EXPECT_LT(pull, 1e-6);
        } else {
            EXPECT_GT(pull, 0.01);
        }
    }
    EXPECT_THROW((void)pseudo_hausdorff(pair.X.V, mx, pair.Y.V, my,
                                        {.epsilon = 0.04, .moving_coverage = 1.5}),
                 InvalidInput);
}

TEST(PseudoHausdorff, TruncationStaysWithinItsBound) {
    const Pair pair = small_pair();
    for (const double alpha : {8.0, 16.0}) {
        const auto exact = evaluate(pair, {.alpha = alpha, .epsilon = 0.02, .truncation = 0});
        for (const double tau : {1e-2, 1e-4, 1e-8}) {
            const auto truncated =
                evaluate(pair, {.alpha = alpha, .epsilon = 0.02, .truncation = tau});
            const double bound = tau / (2 * alpha * (1 - tau));
            EXPECT_LE(std::abs(truncated.value - exact.value) / (exact.value + 0.02), bound) << tau;
            EXPECT_LT(test::relative_error(truncated.differential, exact.differential), 100 * tau)
                << tau;
            EXPECT_LT(truncated.pairs, exact.pairs);
        }
    }
}

// The target points' parts of the coupling are summed with a common factor per thread, set by
// the first query and raised when a later one is far larger: here the near copy of the target
// comes first (cell order: low z) and the far copy's terms exceed its by ~e^1000 at α = 100.
TEST(PseudoHausdorff, DifferentialHoldsWhenTheTargetTermsSpanAThousandOrdersOfMagnitude) {
    const TriangleMesh X = test::noisy_icosphere(1, 0.2, 3);
    const TriangleMesh near = test::noisy_icosphere(1, 0.15, 7);
    Eigen::MatrixX3d Y(2 * near.V.rows(), 3);
    Y << near.V, near.V.rowwise() + Eigen::RowVector3d(0, 0, 10);
    const Eigen::VectorXd mx = lumped_masses(X, MassType::Barycentric);
    Eigen::VectorXd my(Y.rows());
    my << lumped_masses(near, MassType::Barycentric), lumped_masses(near, MassType::Barycentric);
    for (const double truncation : {0.0, 1e-4}) {
        const PseudoHausdorffOptions options{
            .alpha = 100, .epsilon = 0.05, .truncation = truncation};
        const auto value = [&](const TriangleMesh& m) {
            return pseudo_hausdorff(m.V, mx, Y, my, options).value;
        };
        const VertexField analytic = pseudo_hausdorff(X.V, mx, Y, my, options).differential;
        ASSERT_TRUE(analytic.allFinite());
        const VertexField fd = test::finite_difference_gradient(value, X, 1e-6);
        EXPECT_LT(test::relative_error(analytic, fd), 1e-6) << truncation;
    }
}

// Above 2000 points a side's sums run on all threads: here one side is summed in parallel and
// the other not, both ways round (an earlier version scattered only the first thread's terms of
// the target sums into a small source). Central differences at 24 vertices spread over X.
TEST(PseudoHausdorff, DifferentialHoldsWhenOnlyOneSideIsSummedInParallel) {
    const TriangleMesh small = make_limb(3);     // 642 vertices
    const TriangleMesh large = make_limb(4, 9);  // 2562 vertices
    for (const auto& [X, Y] : {std::pair{&small, &large}, std::pair{&large, &small}}) {
        const Eigen::VectorXd mx = lumped_masses(*X, MassType::Barycentric);
        const Eigen::VectorXd my = lumped_masses(*Y, MassType::Barycentric);
        const PseudoHausdorffOptions options{.alpha = 8, .epsilon = mean_edge_length(*Y)};
        const VertexField analytic = pseudo_hausdorff(X->V, mx, Y->V, my, options).differential;
        std::vector<Eigen::Index> sampled;
        for (Eigen::Index i = 0; i < X->V.rows(); i += X->V.rows() / 24) {
            sampled.push_back(i);
        }
        Eigen::MatrixX3d fd(static_cast<Eigen::Index>(sampled.size()), 3);
        Eigen::MatrixX3d expected(fd.rows(), 3);
        for (Eigen::Index k = 0; k < fd.rows(); ++k) {
            const Eigen::Index i = sampled[static_cast<std::size_t>(k)];
            expected.row(k) = analytic.row(i);
            for (int c = 0; c < 3; ++c) {
                constexpr double h = 1e-6;
                Eigen::MatrixX3d plus = X->V;
                Eigen::MatrixX3d minus = X->V;
                plus(i, c) += h;
                minus(i, c) -= h;
                fd(k, c) = (pseudo_hausdorff(plus, mx, Y->V, my, options).value -
                            pseudo_hausdorff(minus, mx, Y->V, my, options).value) /
                           (2 * h);
            }
        }
        EXPECT_LT(test::relative_error(expected, fd), 1e-6)
            << X->V.rows() << " against " << Y->V.rows();
    }
}

#ifdef _OPENMP
// The value and the differential are summed in an order that does not depend on the thread
// count, so that a match gives the same bits on any machine (per-thread partial sums gave
// 0.75 % on one machine and 0.85 % on another).
TEST(PseudoHausdorff, TheValueAndDifferentialAreTheSameOnAnyNumberOfThreads) {
    const TriangleMesh X = make_icosphere(6);  // 40962 vertices: every loop runs in parallel
    const TriangleMesh Y = test::noisy_icosphere(6, 0.2);
    const Eigen::VectorXd mx = lumped_masses(X, MassType::Barycentric);
    const Eigen::VectorXd my = lumped_masses(Y, MassType::Barycentric);
    const PseudoHausdorffOptions options{.alpha = 8, .epsilon = mean_edge_length(Y)};
    const int threads = omp_get_max_threads();
    std::vector<PseudoHausdorffEvaluation> evaluations;
    for (const int count : {1, 2, 3}) {
        omp_set_num_threads(count);
        evaluations.push_back(pseudo_hausdorff(X.V, mx, Y.V, my, options));
    }
    omp_set_num_threads(threads);
    for (const std::size_t k : {1, 2}) {
        EXPECT_EQ(evaluations[k].value, evaluations[0].value) << k + 1 << " threads";
        EXPECT_TRUE(
            (evaluations[k].differential.array() == evaluations[0].differential.array()).all())
            << k + 1 << " threads";
    }
}

// Below the parallel thresholds the sums run without a region of their own, as a match's
// side-by-side flows call them from the threads of a team: there they must neither share
// their loops with that team (a worksharing loop would bind to it, and hang or skip points)
// nor round differently. Each thread of a team of two evaluates a small pair, one side of
// 642 points and one of 2562, in turn as source and target.
TEST(PseudoHausdorff, SmallSetsGiveTheSameBitsFromEachThreadOfATeam) {
    const TriangleMesh small = make_limb(3);     // 642 vertices: no region
    const TriangleMesh large = make_limb(4, 9);  // 2562 vertices: a region of its own
    const Eigen::VectorXd ms = lumped_masses(small, MassType::Barycentric);
    const Eigen::VectorXd ml = lumped_masses(large, MassType::Barycentric);
    const PseudoHausdorffOptions options{.alpha = 8, .epsilon = mean_edge_length(small)};
    const auto evaluate = [&](int which) {
        return which == 0 ? pseudo_hausdorff(small.V, ms, large.V, ml, options)
                          : pseudo_hausdorff(large.V, ml, small.V, ms, options);
    };
    const PseudoHausdorffEvaluation alone[2] = {evaluate(0), evaluate(1)};
    PseudoHausdorffEvaluation in_team[2][2];
#pragma omp parallel num_threads(2)
    {
        const int thread = omp_get_thread_num();
        for (int which = 0; which < 2; ++which) {
            in_team[thread][which] = evaluate(which);
        }
    }
    for (int thread = 0; thread < 2; ++thread) {
        for (int which = 0; which < 2; ++which) {
            const PseudoHausdorffEvaluation& e = in_team[thread][which];
            EXPECT_EQ(e.value, alone[which].value) << "thread " << thread << ", pair " << which;
            EXPECT_EQ(e.pairs, alone[which].pairs) << "thread " << thread << ", pair " << which;
            EXPECT_TRUE((e.differential.array() == alone[which].differential.array()).all())
                << "thread " << thread << ", pair " << which;
        }
    }
}
#endif

TEST(PseudoHausdorff, IsSymmetric) {
    const Pair pair = small_pair();
    const Eigen::VectorXd mx = lumped_masses(pair.X, MassType::Barycentric);
    const Eigen::VectorXd my = lumped_masses(pair.Y, MassType::Barycentric);
    const PseudoHausdorffOptions options{.alpha = 8, .epsilon = 0.01, .truncation = 0};
    EXPECT_NEAR(pseudo_hausdorff(pair.X.V, mx, pair.Y.V, my, options).value,
                pseudo_hausdorff(pair.Y.V, my, pair.X.V, mx, options).value, 1e-13);
}

TEST(PseudoHausdorff, OfIdenticalMeshesIsWithinTheEpsilonOffset) {
    const TriangleMesh mesh = test::noisy_icosphere(3, 0.1);
    const double epsilon = 0.1 * mean_edge_length(mesh);
    for (const double alpha : {4.0, 8.0, 16.0}) {
        const PseudoHausdorffEnergy energy(mesh, {.alpha = alpha, .epsilon = epsilon});
        const double value = energy.value(mesh);
        // f_i ≥ b_i ε^{−2α} gives S ≤ 2P ε^{2α}: d_H ≤ ε((2P)^{1/(2α)} − 1); and d_H > −ε.
        const double P = static_cast<double>(mesh.V.rows());
        EXPECT_LE(value, epsilon * (std::pow(2 * P, 1 / (2 * alpha)) - 1) * (1 + 1e-9)) << alpha;
        EXPECT_GT(value, -epsilon);
    }
}

TEST(PseudoHausdorff, ApproachesTheVertexHausdorffDistanceAsAlphaGrows) {
    // Two different shapes, and two samplings of the same shape (docs/formulas.md §8: the limit is
    // the ε-regularized Hausdorff distance between the vertex sets, not between the surfaces).
    const TriangleMesh sphere = make_icosphere(3);
    TriangleMesh resampled = make_icosphere(2);
    resampled.V = resampled.V *
                  Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    TriangleMesh ellipsoid = resampled;
    ellipsoid.V = ellipsoid.V * Eigen::Vector3d(1.2, 1.0, 0.9).asDiagonal();
    const double epsilon = 1e-3;
    for (const TriangleMesh* target : {&resampled, &ellipsoid}) {
        const double hausdorff = vertex_hausdorff(sphere.V, target->V);
        const double limit = std::sqrt(hausdorff * hausdorff + epsilon * epsilon) - epsilon;
        // Not monotone in α (docs/formulas.md §8's table), but the soft-min bias of small α
        // disappears.
        const auto error = [&](double alpha) {
            const PseudoHausdorffEnergy energy(*target, {.alpha = alpha, .epsilon = epsilon});
            return std::abs(energy.value(sphere) - limit) / limit;
        };
        const double at_1024 = error(1024);
        EXPECT_LT(at_1024, 0.005);
        EXPECT_LT(at_1024, error(2));
        EXPECT_LT(error(256), 0.02);
    }
}

TEST(PseudoHausdorff, IsScaleEquivariantAndStableFromMicroToKilo) {
    const Pair pair = small_pair();
    const auto base = evaluate(pair, {.alpha = 20, .epsilon = 0.01, .truncation = 0});
    for (const double scale : {1e-3, 1e3}) {
        Pair scaled = pair;
        scaled.X.V *= scale;
        scaled.Y.V *= scale;
        for (const double truncation : {0.0, 1e-4}) {
            const auto result =
                evaluate(scaled, {.alpha = 20, .epsilon = 0.01 * scale, .truncation = truncation});
            EXPECT_NEAR(result.value / scale, base.value, 1e-4 * base.value) << scale;
            EXPECT_TRUE(result.differential.allFinite());
            EXPECT_LT(test::relative_error(result.differential, base.differential), 1e-3) << scale;
        }
    }
}

TEST(PseudoHausdorff, NearlyCoincidentMeshesAtHighAlphaStayFinite) {
    const TriangleMesh X = make_icosphere(2);
    const TriangleMesh Y = add_noise(X, 1e-5, 9);
    for (const double alpha : {20.0, 50.0, 150.0}) {
        const PseudoHausdorffEnergy energy(Y, {.alpha = alpha, .epsilon = 1e-4, .truncation = 0});
        const auto result = energy.evaluate(X);
        EXPECT_TRUE(std::isfinite(result.value));
        EXPECT_GT(result.value, 0);  // the naive float64 formula returns −ε here
        EXPECT_TRUE(result.differential.allFinite());
    }
}

TEST(PseudoHausdorff, LinearizationReproducesTheDifferential) {
    const Pair pair = small_pair();
    const PseudoHausdorffEnergy energy(pair.Y, {.alpha = 8, .epsilon = 0.02});
    const auto linearization = energy.linearize(pair.X);
    ASSERT_TRUE(linearization);
    EXPECT_LT(test::relative_error(linearization->A * pair.X.V + linearization->B,
                                   energy.differential(pair.X)),
              1e-12);
    EXPECT_GT(Eigen::VectorXd(linearization->A.diagonal()).minCoeff(), 0);
}

TEST(PseudoHausdorff, AnImplicitL2FlowDecreasesIt) {
    const Pair pair = small_pair();
    const PseudoHausdorffEnergy energy(pair.Y, {.alpha = 8, .epsilon = 0.05});
    L2Metric metric;
    const FlowResult result =
        implicit_euler(pair.X, energy, metric, {.time_step = 0.1, .max_steps = 20});
    ASSERT_TRUE(result.ok()) << result.message;
    for (std::size_t k = 1; k < result.energy.size(); ++k) {
        EXPECT_LT(result.energy[k], result.energy[k - 1]) << k;
    }
    EXPECT_LT(result.energy.back(), 0.7 * result.energy.front());
}

TEST(PseudoHausdorff, RejectsBadInput) {
    const TriangleMesh mesh = make_icosphere(1);
    EXPECT_THROW(PseudoHausdorffEnergy(mesh, {.alpha = 8, .epsilon = 0}), InvalidInput);
    // ε is squared as a coordinate is: beyond the largest coordinate ε² would overflow.
    EXPECT_THROW(PseudoHausdorffEnergy(mesh, {.alpha = 8, .epsilon = 1e300}), InvalidInput);
    EXPECT_THROW(PseudoHausdorffEnergy(mesh, {.alpha = 0.1, .epsilon = 1}), InvalidInput);
    EXPECT_THROW(PseudoHausdorffEnergy(mesh, {.alpha = 8, .epsilon = 1, .truncation = 0.7}),
                 InvalidInput);
    EXPECT_THROW(PseudoHausdorffEnergy(TriangleMesh{}, {.alpha = 8, .epsilon = 1}), InvalidInput);
    const PseudoHausdorffEnergy energy(mesh, {.alpha = 8, .epsilon = 0.1});
    TriangleMesh bad = mesh;
    bad.V(0, 0) = NAN;
    EXPECT_THROW((void)energy.value(bad), InvalidInput);
    EXPECT_THROW(
        (void)pseudo_hausdorff(mesh.V, Eigen::VectorXd::Ones(3), mesh.V,
                               Eigen::VectorXd::Ones(mesh.V.rows()), {.alpha = 8, .epsilon = 0.1}),
        InvalidInput);
}

// Descriptors of a few columns for every point of `mesh`: smooth functions of position, as a
// heat kernel signature is, on the scale of the meshes (lengths ~0.3).
Eigen::MatrixXd smooth_descriptors(const Eigen::MatrixX3d& points) {
    Eigen::MatrixXd descriptors(points.rows(), 2);
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
        descriptors(i, 0) = 0.3 * std::sin(2 * points(i, 0) + points(i, 2));
        descriptors(i, 1) = 0.2 * points(i, 1) * points(i, 1);
    }
    return descriptors;
}

PointDescriptors descriptors_of(const Pair& pair) {
    return {smooth_descriptors(pair.X.V), smooth_descriptors(pair.Y.V)};
}

// docs/formulas.md §8's sums written out in long double, with d_ij = |x_i − y_j|² + |φ_i − ψ_j|² +
// ε².
double augmented_reference(const Pair& pair, const PointDescriptors& descriptors, double alpha,
                           double epsilon) {
    const Eigen::VectorXd mx = lumped_masses(pair.X, MassType::Barycentric);
    const Eigen::VectorXd my = lumped_masses(pair.Y, MassType::Barycentric);
    const Eigen::Index P = pair.X.V.rows();
    const Eigen::Index Q = pair.Y.V.rows();
    std::vector<long double> f(static_cast<std::size_t>(P), 0);
    std::vector<long double> g(static_cast<std::size_t>(Q), 0);
    for (Eigen::Index i = 0; i < P; ++i) {
        for (Eigen::Index j = 0; j < Q; ++j) {
            const long double d =
                (pair.X.V.row(i) - pair.Y.V.row(j)).squaredNorm() +
                (descriptors.moving.row(i) - descriptors.fixed.row(j)).squaredNorm() +
                epsilon * epsilon;
            const long double power = std::pow(d, -static_cast<long double>(alpha));
            f[static_cast<std::size_t>(i)] += my[j] / static_cast<double>(Q) * power;
            g[static_cast<std::size_t>(j)] += mx[i] / static_cast<double>(P) * power;
        }
    }
    long double S = 0;
    for (Eigen::Index i = 0; i < P; ++i) {
        S += mx[i] / static_cast<double>(P) / f[static_cast<std::size_t>(i)];
    }
    for (Eigen::Index j = 0; j < Q; ++j) {
        S += my[j] / static_cast<double>(Q) / g[static_cast<std::size_t>(j)];
    }
    return static_cast<double>(std::pow(S, 1 / (2 * static_cast<long double>(alpha))) - epsilon);
}

TEST(PseudoHausdorffDescriptors, GiveTheDistanceOfTheAugmentedPointSets) {
    const Pair pair = small_pair();
    const PointDescriptors descriptors = descriptors_of(pair);
    for (const double alpha : {2.0, 8.0}) {
        const PseudoHausdorffOptions options{.alpha = alpha, .epsilon = 0.03, .truncation = 0};
        const double expected = augmented_reference(pair, descriptors, alpha, 0.03);
        const PseudoHausdorffEnergy energy(pair.Y, options, descriptors);
        EXPECT_NEAR(energy.value(pair.X), expected, 1e-12 * expected) << alpha;
        // ... larger than without them: every d_ij grows.
        EXPECT_GT(expected, evaluate(pair, options).value);
    }
}

TEST(PseudoHausdorffDescriptors, DifferentialMatchesFiniteDifferences) {
    const Pair pair = small_pair();
    const PointDescriptors descriptors = descriptors_of(pair);
    const Eigen::VectorXd mx = lumped_masses(pair.X, MassType::Barycentric);
    const Eigen::VectorXd my = lumped_masses(pair.Y, MassType::Barycentric);
    for (const double alpha : {4.0, 8.0, 16.0}) {
        for (const double truncation : {0.0, 1e-12}) {
            const PseudoHausdorffOptions options{
                .alpha = alpha, .epsilon = 0.03, .truncation = truncation};
            const auto value = [&](const TriangleMesh& m) {
                return pseudo_hausdorff(m.V, mx, pair.Y.V, my, options, descriptors).value;
            };
            const VertexField fd = test::finite_difference_gradient(value, pair.X, 1e-6);
            const VertexField analytic =
                pseudo_hausdorff(pair.X.V, mx, pair.Y.V, my, options, descriptors).differential;
            EXPECT_LT(test::relative_error(analytic, fd), 1e-6)
                << "alpha " << alpha << " truncation " << truncation;
        }
    }
}

TEST(PseudoHausdorffDescriptors, TruncationStaysWithinItsBound) {
    const Pair pair = small_pair();
    const PointDescriptors descriptors = descriptors_of(pair);
    const Eigen::VectorXd mx = lumped_masses(pair.X, MassType::Barycentric);
    const Eigen::VectorXd my = lumped_masses(pair.Y, MassType::Barycentric);
    const auto at = [&](double tau) {
        return pseudo_hausdorff(pair.X.V, mx, pair.Y.V, my,
                                {.alpha = 8, .epsilon = 0.02, .truncation = tau}, descriptors);
    };
    const auto exact = at(0);
    for (const double tau : {1e-2, 1e-4, 1e-8}) {
        const auto truncated = at(tau);
        EXPECT_LE(std::abs(truncated.value - exact.value) / (exact.value + 0.02),
                  tau / (16 * (1 - tau)))
            << tau;
        EXPECT_LT(test::relative_error(truncated.differential, exact.differential), 100 * tau)
            << tau;
        EXPECT_LT(truncated.pairs, exact.pairs);
    }
}

TEST(PseudoHausdorffDescriptors, EqualDescriptorsChangeNothing) {
    const Pair pair = small_pair();
    const PseudoHausdorffOptions options{.alpha = 8, .epsilon = 0.02, .truncation = 1e-4};
    const PseudoHausdorffEnergy plain(pair.Y, options);
    const PseudoHausdorffEnergy constant(pair.Y, options,
                                         {Eigen::MatrixXd::Constant(pair.X.V.rows(), 3, 0.7),
                                          Eigen::MatrixXd::Constant(pair.Y.V.rows(), 3, 0.7)});
    const auto a = plain.evaluate(pair.X);
    const auto b = constant.evaluate(pair.X);
    EXPECT_DOUBLE_EQ(b.value, a.value);
    EXPECT_LT(test::relative_error(b.differential, a.differential), 1e-14);
}

// The energy tabulates the descriptors' part of every pair's distance once (small sets, as a
// match's coarsest level); pseudo_hausdorff() computes it per pair. Both must give the same
// numbers to the bit, or a match would depend on which path its level took.
TEST(PseudoHausdorffDescriptors, TabulatedAndPerPairDistancesAgreeToTheBit) {
    const Pair pair = small_pair();
    const PointDescriptors descriptors = descriptors_of(pair);
    const Eigen::VectorXd my = lumped_masses(pair.Y, MassType::Barycentric);
    TriangleMesh moved = pair.X;
    moved.V.col(0) *= 1.3;  // another placement than the one the energy was first asked of
    for (const double alpha : {3.0, 8.0}) {
        for (const double truncation : {0.0, 1e-2}) {
            const PseudoHausdorffOptions options{
                .alpha = alpha, .epsilon = 0.03, .truncation = truncation};
            const PseudoHausdorffEnergy energy(pair.Y, options, descriptors);
            for (const TriangleMesh* mesh : {&pair.X, static_cast<const TriangleMesh*>(&moved)}) {
                const Eigen::VectorXd mx = lumped_masses(*mesh, MassType::Barycentric);
                const auto tabulated = energy.evaluate(*mesh);
                const auto per_pair =
                    pseudo_hausdorff(mesh->V, mx, pair.Y.V, my, options, descriptors);
                EXPECT_EQ(tabulated.value, per_pair.value) << alpha << " " << truncation;
                EXPECT_EQ(tabulated.pairs, per_pair.pairs);
                EXPECT_TRUE(tabulated.differential == per_pair.differential)
                    << alpha << " " << truncation;
            }
        }
    }
}

TEST(PseudoHausdorffDescriptors, PullEachPointTowardsTheAlikeOfTwoEquallyNearOnes) {
    // Two moving points midway between two fixed ones, the first alike the one at −x, the
    // second alike the one at +x. Without descriptors the mirror symmetry leaves no pull along x.
    Eigen::MatrixX3d X(2, 3);
    X << 0, 0.1, 0, 0, -0.1, 0;
    Eigen::MatrixX3d Y(2, 3);
    Y << -1, 0, 0, 1, 0, 0;
    const Eigen::VectorXd masses = Eigen::VectorXd::Ones(2);
    const PseudoHausdorffOptions options{.alpha = 8, .epsilon = 0.1, .truncation = 0};
    const auto plain = pseudo_hausdorff(X, masses, Y, masses, options);
    EXPECT_NEAR(plain.differential(0, 0), 0, 1e-12 * plain.differential.norm());
    EXPECT_NEAR(plain.differential(1, 0), 0, 1e-12 * plain.differential.norm());
    Eigen::MatrixXd kinds(2, 1);
    kinds << 0, 0.5;
    const auto guided = pseudo_hausdorff(X, masses, Y, masses, options, {kinds, kinds});
    // Descent goes along −differential: the first point to −x, the second to +x.
    EXPECT_GT(guided.differential(0, 0), 0.5 * guided.differential.row(0).norm());
    EXPECT_LT(guided.differential(1, 0), -0.5 * guided.differential.row(1).norm());
}

TEST(PseudoHausdorffDescriptors, RejectsDescriptorsThatDoNotFit) {
    const Pair pair = small_pair();
    const PseudoHausdorffOptions options{.alpha = 8, .epsilon = 0.1};
    const Eigen::Index P = pair.X.V.rows();
    const Eigen::Index Q = pair.Y.V.rows();
    EXPECT_THROW(PseudoHausdorffEnergy(pair.Y, options,
                                       {Eigen::MatrixXd::Zero(P, 2), Eigen::MatrixXd::Zero(Q, 3)}),
                 InvalidInput);
    EXPECT_THROW(
        PseudoHausdorffEnergy(pair.Y, options,
                              {Eigen::MatrixXd::Zero(P, 2), Eigen::MatrixXd::Zero(Q + 1, 2)}),
        InvalidInput);
    Eigen::MatrixXd with_nan = Eigen::MatrixXd::Zero(Q, 2);
    with_nan(3, 1) = NAN;
    EXPECT_THROW(PseudoHausdorffEnergy(pair.Y, options, {Eigen::MatrixXd::Zero(P, 2), with_nan}),
                 InvalidInput);
    const PseudoHausdorffEnergy energy(
        pair.Y, options, {Eigen::MatrixXd::Zero(P + 1, 2), Eigen::MatrixXd::Zero(Q, 2)});
    EXPECT_THROW((void)energy.value(pair.X), InvalidInput);  // one descriptor row too many
    EXPECT_THROW(
        (void)pseudo_hausdorff(pair.X.V, lumped_masses(pair.X, MassType::Barycentric), pair.Y.V,
                               lumped_masses(pair.Y, MassType::Barycentric), options,
                               {Eigen::MatrixXd::Zero(P - 1, 2), Eigen::MatrixXd::Zero(Q, 2)}),
        InvalidInput);
}

}  // namespace
}  // namespace genflow
