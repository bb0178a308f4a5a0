// SPDX-License-Identifier: MIT
#include "genflow/metrics/sparse_metric.h"

#include <cmath>

#include "metrics/metric_support.h"
#include "numerics/spd_solver.h"
#include "operators/triangle.h"

namespace genflow {

struct SparseMetric::Impl {
    explicit Impl(Factorization factorization)
        : metric_solver(factorization), shifted_solver(factorization) {}

    Eigen::SparseMatrix<double> G;
    detail::SpdSolver metric_solver;   // factors G (pinned)
    detail::SpdSolver shifted_solver;  // factors G + dt·A (pinned)
    std::vector<bool> fixed;           // the mask in force since the last update()
    bool ready = false;
};

SparseMetric::SparseMetric(Factorization factorization)
    : impl_(std::make_unique<Impl>(factorization)) {}
SparseMetric::~SparseMetric() = default;
SparseMetric::SparseMetric(SparseMetric&&) noexcept = default;
SparseMetric& SparseMetric::operator=(SparseMetric&&) noexcept = default;

void SparseMetric::update(const TriangleMesh& mesh) {
    update_alongside(mesh, {});
}

void SparseMetric::update_alongside(const TriangleMesh& mesh, const std::function<void()>& task) {
    detail::require_valid_mesh(mesh, "SparseMetric::update");
    if (mesh.F.rows() == 0) {
        throw InvalidInput("SparseMetric::update: mesh has no faces");
    }
    detail::require_mask_size(fixed_, mesh.V.rows(), "SparseMetric::update");
    impl_->ready = false;
    impl_->G = assemble(mesh);
    impl_->G.makeCompressed();
    if (impl_->G.rows() != mesh.V.rows() || impl_->G.cols() != mesh.V.rows()) {
        throw InvalidInput("SparseMetric::update: assemble() must return a #V×#V matrix");
    }
    impl_->fixed = fixed_;
    if (impl_->fixed.empty()) {  // nothing to pin: G itself, without a copy
        impl_->metric_solver.compute(impl_->G, "SparseMetric::update", task);
    } else {
        Eigen::SparseMatrix<double> pinned = impl_->G;
        detail::pin_fixed(pinned, impl_->fixed);
        impl_->metric_solver.compute(pinned, "SparseMetric::update", task);
    }
    impl_->ready = true;
}

VertexField SparseMetric::gradient(const VertexField& dEdX) const {
    if (!impl_->ready) {
        throw InvalidInput("SparseMetric::gradient: update() was not called");
    }
    detail::require_rows(dEdX, impl_->G.rows(), "SparseMetric::gradient");
    return impl_->metric_solver.solve(detail::zero_fixed_rows(dEdX, impl_->fixed));
}

VertexField SparseMetric::apply(const VertexField& U) const {
    if (!impl_->ready) {
        throw InvalidInput("SparseMetric::apply: update() was not called");
    }
    detail::require_rows(U, impl_->G.rows(), "SparseMetric::apply");
    return impl_->G * U;
}

VertexField SparseMetric::shifted_gradient(const Eigen::SparseMatrix<double>& A, double dt,
                                           const VertexField& R) {
    if (!impl_->ready) {
        throw InvalidInput("SparseMetric::shifted_gradient: update() was not called");
    }
    detail::require_rows(R, impl_->G.rows(), "SparseMetric::shifted_gradient");
    if (A.rows() != impl_->G.rows() || A.cols() != impl_->G.cols()) {
        throw InvalidInput("SparseMetric::shifted_gradient: A must be #V×#V");
    }
    if (!detail::finite_at_least(dt, 0)) {
        throw InvalidInput("SparseMetric::shifted_gradient: dt must be non-negative and finite");
    }
    Eigen::SparseMatrix<double> shifted = impl_->G + dt * A;
    shifted.makeCompressed();
    detail::pin_fixed(shifted, impl_->fixed);
    impl_->shifted_solver.compute(shifted, "SparseMetric::shifted_gradient");
    return impl_->shifted_solver.solve(detail::zero_fixed_rows(R, impl_->fixed));
}

const Eigen::SparseMatrix<double>& SparseMetric::matrix() const {
    return impl_->G;
}

int SparseMetric::symbolic_analyses() const {
    return impl_->metric_solver.analyses() + impl_->shifted_solver.analyses();
}

}  // namespace genflow
