// SPDX-License-Identifier: MIT
// L-BFGS's memory in a metric (flows/quasi_newton_memory.h): the metric's gradient without
// memory, the secant equation on the newest pair, a descent direction always, and steps that
// do not curve upward left out.
#include "flows/quasi_newton_memory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "genflow/mesh/primitives.h"
#include "genflow/metrics/sobolev_metric.h"
#include "genflow/operators/mesh_size.h"

namespace genflow::detail {
namespace {

double dot(const VertexField& a, const VertexField& b) {
    return (a.array() * b.array()).sum();
}

VertexField random_field(Eigen::Index rows, std::mt19937& random) {
    std::normal_distribution<double> normal;
    VertexField field(rows, 3);
    for (Eigen::Index k = 0; k < field.size(); ++k) {
        field.data()[k] = normal(random);
    }
    return field;
}

struct MetricOnASphere {
    TriangleMesh mesh = make_icosphere(2);
    H1Metric metric{{.lambda = std::pow(3 * mean_edge_length(mesh), 2)}};
    MetricOnASphere() { metric.update(mesh); }
};

TEST(QuasiNewtonMemory, IsTheMetricsGradientWithoutMemory) {
    const MetricOnASphere sphere;
    std::mt19937 random(1);
    const VertexField differential = random_field(sphere.mesh.V.rows(), random);
    QuasiNewtonMemory memory(5);
    memory.record(sphere.mesh.V, differential, sphere.metric);  // an origin, no pair yet
    EXPECT_TRUE(memory.empty());
    EXPECT_LT((memory.direction(differential, sphere.metric) - sphere.metric.gradient(differential))
                  .norm(),
              1e-12 * differential.norm());
}

// From positions X_k with differentials along a quadratic energy's gradient (Hessian diagonal
// and positive, so every step curves upward): H y = s on the newest pair to rounding, whatever
// the older pairs and the metric, and −H dE descends for any dE (H is positive definite).
TEST(QuasiNewtonMemory, SatisfiesTheSecantEquationAndDescends) {
    const MetricOnASphere sphere;
    std::mt19937 random(2);
    const Eigen::Index n = sphere.mesh.V.rows();
    const Eigen::ArrayXd hessian = random_field(n, random).reshaped().array().abs() + 0.1;
    const auto differential = [&](const VertexField& x) {
        VertexField d(n, 3);
        d.reshaped() = (hessian * x.reshaped().array()).matrix();
        return d;
    };
    QuasiNewtonMemory memory(3);
    VertexField x = sphere.mesh.V;
    VertexField s;
    VertexField y;
    for (int step = 0; step < 6; ++step) {  // more steps than the memory holds
        memory.record(x, differential(x), sphere.metric);
        const VertexField next = x + 0.1 * random_field(n, random);
        s = next - x;
        y = differential(next) - differential(x);
        x = next;
    }
    memory.record(x, differential(x), sphere.metric);
    ASSERT_FALSE(memory.empty());
    EXPECT_LT((memory.direction(y, sphere.metric) - s).norm(), 1e-10 * s.norm());
    for (int trial = 0; trial < 5; ++trial) {
        const VertexField gradient = random_field(n, random);
        EXPECT_GT(dot(gradient, memory.direction(gradient, sphere.metric)), 0) << trial;
    }
}

// A step along which the differential does not grow (sᵀy ≤ 0, as on the concave parts of d_H)
// would make H indefinite: it is not kept.
TEST(QuasiNewtonMemory, LeavesOutStepsThatDoNotCurveUpward) {
    const MetricOnASphere sphere;
    std::mt19937 random(3);
    const VertexField gradient = random_field(sphere.mesh.V.rows(), random);
    QuasiNewtonMemory memory(5);
    memory.record(sphere.mesh.V, gradient, sphere.metric);
    const VertexField s = 0.1 * gradient;
    memory.record(sphere.mesh.V + s, gradient - s, sphere.metric);  // sᵀy = −‖s‖² < 0
    EXPECT_TRUE(memory.empty());
    memory.record(sphere.mesh.V + 2 * s, gradient, sphere.metric);  // sᵀy = ‖s‖² > 0
    EXPECT_FALSE(memory.empty());
    memory.clear();
    EXPECT_TRUE(memory.empty());
}

}  // namespace
}  // namespace genflow::detail
