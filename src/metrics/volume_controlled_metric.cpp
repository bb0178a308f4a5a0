// SPDX-License-Identifier: MIT
#include "genflow/metrics/volume_controlled_metric.h"

#include <cmath>
#include <string>
#include <utility>

#include "genflow/exceptions.h"
#include "genflow/operators/normals.h"
#include "metrics/metric_support.h"
#include "numerics/krylov.h"
#include "numerics/spd_solver.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

// n×3 field ↔ 3n vector (column-major: all x, then all y, then all z).
Eigen::VectorXd flatten(const VertexField& field) {
    return Eigen::Map<const Eigen::VectorXd>(field.data(), field.size());
}
VertexField unflatten(const Eigen::VectorXd& vector) {
    return Eigen::Map<const VertexField>(vector.data(), vector.size() / 3, 3);
}

}  // namespace

struct VolumeControlledMetric::Impl {
    explicit Impl(Factorization factorization) : preconditioner(factorization) {}

    Eigen::VectorXd masses;                 // D, floored
    Eigen::MatrixX3d normals;               // N (unit, zero where undefined)
    Eigen::MatrixX3i faces;                 // the connectivity `adjacency` was built for
    Eigen::SparseMatrix<double> adjacency;  // A₊: one-ring with self-loops, ones
    Eigen::VectorXd ring_sizes;             // |N⁺(j)|
    Eigen::VectorXd ring_areas;             // a = Ψ m
    std::vector<bool> fixed;
    detail::SpdSolver preconditioner;  // D + dt·A
    int last_iterations = 0;
    bool ready = false;

    VertexField zero_fixed(VertexField field) const {
        return detail::zero_fixed_rows(std::move(field), fixed);
    }

    // Nᵀ v: the normal speeds of v.
    Eigen::VectorXd normal_speeds(const VertexField& v) const {
        return (normals.array() * v.array()).rowwise().sum();
    }

    // S f = Ψᵀ diag(1/a) Ψ D f: normal speeds averaged over the one-rings of the one-rings.
    Eigen::VectorXd averaged(const Eigen::VectorXd& f) const {
        const Eigen::VectorXd psi_mf =
            adjacency * (masses.cwiseProduct(f).cwiseQuotient(ring_sizes));
        return (adjacency * psi_mf.cwiseQuotient(ring_areas)).cwiseQuotient(ring_sizes);
    }

    // P v = N S Nᵀ v.
    VertexField project(const VertexField& v) const {
        return normals.array().colwise() * averaged(normal_speeds(v)).array();
    }

    // B v = v − (1 − λ) P v on the free vertices (fixed rows stay zero).
    VertexField apply_b(const VertexField& v, double lambda) const {
        const VertexField free = zero_fixed(v);
        return zero_fixed(free - (1 - lambda) * project(free));
    }
};

VolumeControlledMetric::VolumeControlledMetric(VolumeControlledOptions options)
    : options_(options), impl_(std::make_unique<Impl>(options.factorization)) {
    if (!detail::finite_above(options_.lambda, 0) || options_.lambda > 1) {
        throw InvalidInput("VolumeControlledMetric: lambda must lie in (0, 1], got " +
                           std::to_string(options_.lambda));
    }
    if (!detail::finite_above(options_.tolerance, 0) || options_.tolerance >= 1) {
        throw InvalidInput("VolumeControlledMetric: tolerance must lie in (0, 1)");
    }
}
VolumeControlledMetric::~VolumeControlledMetric() = default;
VolumeControlledMetric::VolumeControlledMetric(VolumeControlledMetric&&) noexcept = default;
VolumeControlledMetric& VolumeControlledMetric::operator=(VolumeControlledMetric&&) noexcept =
    default;

void VolumeControlledMetric::update(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "VolumeControlledMetric::update");
    if (mesh.F.rows() == 0) {
        throw InvalidInput("VolumeControlledMetric::update: mesh has no faces");
    }
    detail::require_mask_size(fixed_, mesh.V.rows(), "VolumeControlledMetric::update");
    auto& d = *impl_;
    d.ready = false;
    const Eigen::Index n = mesh.V.rows();
    d.masses = detail::floored_lumped_masses(mesh, MassType::Barycentric);
    d.normals = vertex_normals(mesh);
    if (d.faces.rows() != mesh.F.rows() || d.faces != mesh.F || d.adjacency.rows() != n) {
        // Depends on connectivity only: built once per flow.
        d.faces = mesh.F;
        std::vector<Eigen::Triplet<double>> triplets;
        triplets.reserve(static_cast<std::size_t>(6 * mesh.F.rows() + n));
        for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
            for (int k = 0; k < 3; ++k) {
                triplets.emplace_back(mesh.F(f, k), mesh.F(f, (k + 1) % 3), 1.0);
                triplets.emplace_back(mesh.F(f, (k + 1) % 3), mesh.F(f, k), 1.0);
            }
        }
        for (Eigen::Index i = 0; i < n; ++i) {
            triplets.emplace_back(i, i, 1.0);
        }
        d.adjacency.resize(n, n);
        d.adjacency.setFromTriplets(triplets.begin(), triplets.end(),
                                    [](double, double) { return 1.0; });
        d.ring_sizes = d.adjacency * Eigen::VectorXd::Ones(n);
    }
    d.ring_areas = d.adjacency * d.masses.cwiseQuotient(d.ring_sizes);
    d.fixed = fixed_;
    d.ready = true;
}

VertexField VolumeControlledMetric::gradient(const VertexField& dEdX) const {
    if (!impl_->ready) {
        throw InvalidInput("VolumeControlledMetric::gradient: update() was not called");
    }
    detail::require_rows(dEdX, impl_->masses.size(), "VolumeControlledMetric::gradient");
    const VertexField l2 = dEdX.array().colwise() / impl_->masses.array();
    return impl_->apply_b(l2, options_.lambda);
}

VertexField VolumeControlledMetric::apply(const VertexField& U) const {
    if (!impl_->ready) {
        throw InvalidInput("VolumeControlledMetric::apply: update() was not called");
    }
    detail::require_rows(U, impl_->masses.size(), "VolumeControlledMetric::apply");
    const auto& d = *impl_;
    // G U = D B⁻¹ U: solve (D B) y = D U by CG; D B is symmetric positive definite.
    const auto DB = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd {
        const VertexField By = d.apply_b(unflatten(y), options_.lambda);
        VertexField result = By.array().colwise() * d.masses.array();
        // Fixed rows: identity, so the operator stays SPD on the whole space.
        detail::copy_fixed_rows(result, unflatten(y), d.fixed);
        return flatten(result);
    };
    const VertexField rhs = d.zero_fixed(U).array().colwise() * d.masses.array();
    const auto solved =
        detail::conjugate_gradient(DB, flatten(rhs), flatten(d.zero_fixed(U)), options_.tolerance,
                                   10 * static_cast<int>(rhs.size()));
    if (!solved.converged) {
        throw SolverError("VolumeControlledMetric::apply: CG did not converge (residual " +
                          std::to_string(solved.relative_residual) + ")");
    }
    return d.masses.asDiagonal() * unflatten(solved.x);
}

VertexField VolumeControlledMetric::shifted_gradient(const Eigen::SparseMatrix<double>& A,
                                                     double dt, const VertexField& R) {
    if (!impl_->ready) {
        throw InvalidInput("VolumeControlledMetric::shifted_gradient: update() was not called");
    }
    auto& d = *impl_;
    const Eigen::Index n = d.masses.size();
    detail::require_rows(R, n, "VolumeControlledMetric::shifted_gradient");
    if (A.rows() != n || A.cols() != n || !detail::finite_at_least(dt, 0)) {
        throw InvalidInput(
            "VolumeControlledMetric::shifted_gradient: A must be #V×#V and dt finite, >= 0");
    }
    // H = D + dt·A with the fixed rows pinned, factored once: every solve below is with it.
    Eigen::SparseMatrix<double> fairing = dt * A;
    for (Eigen::Index i = 0; i < n; ++i) {
        fairing.coeffRef(i, i) += d.masses[i];
    }
    detail::pin_fixed(fairing, d.fixed);
    fairing.makeCompressed();
    d.preconditioner.compute(fairing, "VolumeControlledMetric::shifted_gradient");

    // (D B⁻¹ + dt A) y = R, i.e. (D + dt A B) z = R with y = B z. B = I − (1 − λ) Zf N S Nᵀ Zf
    // (Zf zeroes the fixed rows) moves the normal speeds f = Nᵀ Zf z alone, so with
    // u = Zf N S f and dt·A·u = H u − D u on the free rows,
    //     z = h + (1 − λ)(u − H⁻¹ D u),   h = H⁻¹ Zf R,
    //     y = B z = z − (1 − λ) u = h − (1 − λ) H⁻¹ D u,
    // and f solves the n×n system
    //     f − (1 − λ) Nᵀ Zf (u − H⁻¹ D u) = Nᵀ Zf h.
    // GMRES on it applies one solve with H a step and no product with A; each step's H⁻¹ D u
    // is its image, from which GMRES combines H⁻¹ D u for the solution f without another solve.
    const double softened = 1 - options_.lambda;
    const auto normal_speeds = [&](const VertexField& v) {
        return d.normal_speeds(d.zero_fixed(v));  // Nᵀ Zf v
    };
    const auto system = [&](const Eigen::VectorXd& f, Eigen::MatrixXd& image) -> Eigen::VectorXd {
        const VertexField u = d.zero_fixed(d.normals.array().colwise() * d.averaged(f).array());
        image = d.preconditioner.solve(u.array().colwise() * d.masses.array());
        return f - softened * normal_speeds(u - image);
    };
    const VertexField h = d.preconditioner.solve(d.zero_fixed(R));
    const auto solved = detail::gmres(system, normal_speeds(h), options_.tolerance, 50, 1000);
    d.last_iterations = solved.iterations;
    if (!solved.converged) {
        throw SolverError("VolumeControlledMetric::shifted_gradient: GMRES did not converge in " +
                          std::to_string(solved.iterations) + " iterations (residual " +
                          std::to_string(solved.relative_residual) + ")");
    }
    if (solved.image.size() == 0) {
        return h;  // f = 0: no normal speed to soften
    }
    return h - softened * solved.image;
}

VertexField VolumeControlledMetric::volume_changing_part(const VertexField& v) const {
    if (!impl_->ready) {
        throw InvalidInput("VolumeControlledMetric::volume_changing_part: update() was not called");
    }
    detail::require_rows(v, impl_->masses.size(), "VolumeControlledMetric::volume_changing_part");
    return impl_->project(v);
}

int VolumeControlledMetric::last_iterations() const {
    return impl_->last_iterations;
}

}  // namespace genflow
