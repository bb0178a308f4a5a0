// SPDX-License-Identifier: MIT
#include "genflow/metrics/quasi_isometric_metric.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "genflow/operators/area.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/normals.h"
#include "metrics/metric_support.h"
#include "numerics/spd_solver.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

// Adds the 3×3 blocks of the edge term w·(a aᵀ)⊗(d dᵀ), a = e_i − e_j.
void add_edge_blocks(std::vector<Eigen::Triplet<double>>& triplets, int i, int j,
                     const Eigen::Vector3d& d, double weight) {
    const Eigen::Matrix3d block = weight * d * d.transpose();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
            const double b = block(r, c);
            triplets.emplace_back(3 * i + r, 3 * i + c, b);
            triplets.emplace_back(3 * j + r, 3 * j + c, b);
            triplets.emplace_back(3 * i + r, 3 * j + c, -b);
            triplets.emplace_back(3 * j + r, 3 * i + c, -b);
        }
    }
}

// The ray parameter t > t_min at which x + t·direction crosses the triangle, or +inf
// (Möller–Trumbore).
double ray_hit(const Eigen::Vector3d& x, const Eigen::Vector3d& direction, const Eigen::Vector3d& a,
               const Eigen::Vector3d& b, const Eigen::Vector3d& c, double t_min) {
    constexpr double kNone = std::numeric_limits<double>::infinity();
    const Eigen::Vector3d e1 = b - a;
    const Eigen::Vector3d e2 = c - a;
    const Eigen::Vector3d p = direction.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300) {
        return kNone;
    }
    const Eigen::Vector3d s = x - a;
    const double u = s.dot(p) / det;
    if (u < 0 || u > 1) {
        return kNone;
    }
    const Eigen::Vector3d q = s.cross(e1);
    const double v = direction.dot(q) / det;
    if (v < 0 || u + v > 1) {
        return kNone;
    }
    const double t = e2.dot(q) / det;
    return t > t_min ? t : kNone;
}

// `count` vertices spread over the mesh: farthest-point sampling from the vertex farthest
// from the centroid (deterministic).
std::vector<int> farthest_point_samples(const Eigen::MatrixX3d& V, int count) {
    std::vector<int> samples;
    const Eigen::Index n = V.rows();
    if (n == 0 || count <= 0) {
        return samples;
    }
    const Eigen::RowVector3d centroid = V.colwise().mean();
    Eigen::VectorXd distance2 = (V.rowwise() - centroid).rowwise().squaredNorm();
    for (int k = 0; k < std::min<Eigen::Index>(count, n); ++k) {
        Eigen::Index next = 0;
        distance2.maxCoeff(&next);
        samples.push_back(static_cast<int>(next));
        distance2 = distance2.cwiseMin((V.rowwise() - V.row(next)).rowwise().squaredNorm().eval());
    }
    return samples;
}

}  // namespace

std::vector<std::pair<int, int>> cross_limb_pairs(const TriangleMesh& mesh, int count) {
    detail::require_valid_mesh(mesh, "cross_limb_pairs");
    std::vector<std::pair<int, int>> pairs;
    if (count <= 0 || mesh.F.rows() == 0) {
        return pairs;
    }
    const Eigen::MatrixX3d normals = vertex_normals(mesh);
    const double t_min = 1e-9 * bounding_box_diagonal(mesh);
    const std::vector<int> samples = farthest_point_samples(mesh.V, count);
    std::vector<int> partner(samples.size(), -1);
#pragma omp parallel for schedule(dynamic, 4)
    for (std::size_t s = 0; s < samples.size(); ++s) {
        const int i = samples[s];
        const Eigen::Vector3d x = mesh.V.row(i).transpose();
        const Eigen::Vector3d inward = -normals.row(i).transpose();
        if (inward.squaredNorm() == 0) {
            continue;
        }
        double nearest = std::numeric_limits<double>::infinity();
        Eigen::Index hit_face = -1;
        for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
            const Eigen::RowVector3i face = mesh.F.row(f);
            if (face[0] == i || face[1] == i || face[2] == i) {
                continue;
            }
            const double t =
                ray_hit(x, inward, mesh.V.row(face[0]).transpose(), mesh.V.row(face[1]).transpose(),
                        mesh.V.row(face[2]).transpose(), t_min);
            if (t < nearest) {
                nearest = t;
                hit_face = f;
            }
        }
        if (hit_face < 0) {
            continue;
        }
        const Eigen::Vector3d hit = x + nearest * inward;
        double closest = std::numeric_limits<double>::infinity();
        for (int corner = 0; corner < 3; ++corner) {
            const int v = mesh.F(hit_face, corner);
            const double d2 = (mesh.V.row(v).transpose() - hit).squaredNorm();
            if (d2 < closest) {
                closest = d2;
                partner[s] = v;
            }
        }
    }
    std::set<std::pair<int, int>> seen;
    for (std::size_t s = 0; s < samples.size(); ++s) {
        if (partner[s] < 0 || partner[s] == samples[s]) {
            continue;
        }
        const std::pair<int, int> pair{std::min(samples[s], partner[s]),
                                       std::max(samples[s], partner[s])};
        if (seen.insert(pair).second) {
            pairs.push_back(pair);
        }
    }
    return pairs;
}

struct QuasiIsometricMetric::Impl {
    Eigen::SparseMatrix<double> G;
    detail::SpdSolver metric_solver;
    detail::SpdSolver shifted_solver;
    std::vector<bool> fixed_vertices;     // the mask in force since the last update()
    std::vector<bool> fixed_coordinates;  // the same per row of G (empty if no mask)
    std::vector<std::pair<int, int>> fake_edges;
    Eigen::Index fake_edges_for = -1;  // the vertex count they were chosen for
    bool ready = false;
    int updates_since_build = 0;
};

QuasiIsometricMetric::QuasiIsometricMetric(const QuasiIsometricOptions& options)
    : options_(options), impl_(std::make_unique<Impl>()) {}
QuasiIsometricMetric::~QuasiIsometricMetric() = default;
QuasiIsometricMetric::QuasiIsometricMetric(QuasiIsometricMetric&&) noexcept = default;
QuasiIsometricMetric& QuasiIsometricMetric::operator=(QuasiIsometricMetric&&) noexcept = default;

void QuasiIsometricMetric::update(const TriangleMesh& mesh) {
    constexpr const char* kCaller = "QuasiIsometricMetric::update";
    detail::require_valid_mesh(mesh, kCaller);
    if (mesh.F.rows() == 0) {
        throw InvalidInput(std::string(kCaller) + ": mesh has no faces");
    }
    if (!detail::finite_at_least(options_.rigidity_length, 0) ||
        !detail::finite_at_least(options_.fake_edge_weight, 0) || options_.fake_edges < 0 ||
        options_.refresh_interval < 1) {
        throw InvalidInput(std::string(kCaller) +
                           ": rigidity_length and fake_edge_weight must be finite and "
                           "non-negative, fake_edges non-negative, refresh_interval positive");
    }
    const Eigen::Index n = mesh.V.rows();
    detail::require_mask_size(fixed_, n, kCaller);
    if (impl_->ready && impl_->G.rows() == 3 * n && impl_->fixed_vertices == fixed_ &&
        ++impl_->updates_since_build < options_.refresh_interval) {
        return;  // G of a few steps ago: still SPD, so its gradient still descends
    }
    impl_->updates_since_build = 0;
    impl_->ready = false;

    const Eigen::VectorXd masses = detail::floored_lumped_masses(mesh, MassType::Barycentric);
    const double diagonal = bounding_box_diagonal(mesh);
    const double lambda = std::pow(options_.rigidity_length * diagonal, 2);
    // |d_e|² is floored so that a collapsed edge stiffens its neighbourhood without making G
    // infinite.
    const double mean_edge = mean_edge_length(mesh);
    const double floor2 = std::max(1e-6 * mean_edge * mean_edge, 1e-300);

    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<std::size_t>(3 * n + 108 * mesh.F.rows()));
    for (Eigen::Index i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) {
            triplets.emplace_back(3 * static_cast<int>(i) + c, 3 * static_cast<int>(i) + c,
                                  masses[i]);
        }
    }
    // Each face gives each of its edges a third of its area, so an interior edge gets
    // A_e = (A_f1 + A_f2)/3 over its two faces.
    const Eigen::VectorXd areas = face_areas(mesh);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            const int i = mesh.F(f, k);
            const int j = mesh.F(f, (k + 1) % 3);
            const Eigen::Vector3d d = (mesh.V.row(i) - mesh.V.row(j)).transpose();
            const double length2 = std::max(d.squaredNorm(), floor2);
            add_edge_blocks(triplets, i, j, d, lambda * areas[f] / 3 / (length2 * length2));
        }
    }
    if (options_.fake_edges > 0 && impl_->fake_edges_for != n) {
        impl_->fake_edges = cross_limb_pairs(mesh, options_.fake_edges);
        impl_->fake_edges_for = n;
    }
    if (options_.fake_edges > 0) {
        for (const auto& [i, j] : impl_->fake_edges) {  // w_f = β·½(m_i + m_j)/ℓ_f⁴
            const Eigen::Vector3d d = (mesh.V.row(i) - mesh.V.row(j)).transpose();
            const double length2 = std::max(d.squaredNorm(), floor2);
            add_edge_blocks(triplets, i, j, d,
                            lambda * options_.fake_edge_weight * 0.5 * (masses[i] + masses[j]) /
                                (length2 * length2));
        }
    }
    impl_->G.resize(3 * n, 3 * n);
    impl_->G.setFromTriplets(triplets.begin(), triplets.end());
    impl_->G.makeCompressed();

    impl_->fixed_vertices = fixed_;
    impl_->fixed_coordinates.clear();
    for (const bool fixed : fixed_) {
        impl_->fixed_coordinates.insert(impl_->fixed_coordinates.end(), 3, fixed);
    }
    Eigen::SparseMatrix<double> pinned = impl_->G;
    detail::pin_fixed(pinned, impl_->fixed_coordinates);
    impl_->metric_solver.compute(pinned, kCaller);
    impl_->ready = true;
}

VertexField QuasiIsometricMetric::gradient(const VertexField& dEdX) const {
    if (!impl_->ready) {
        throw InvalidInput("QuasiIsometricMetric::gradient: update() was not called");
    }
    detail::require_rows(dEdX, impl_->G.rows() / 3, "QuasiIsometricMetric::gradient");
    const VertexField rhs = detail::zero_fixed_rows(dEdX, impl_->fixed_vertices);
    return detail::deinterleave(impl_->metric_solver.solve(detail::interleave(rhs)).col(0));
}

VertexField QuasiIsometricMetric::apply(const VertexField& U) const {
    if (!impl_->ready) {
        throw InvalidInput("QuasiIsometricMetric::apply: update() was not called");
    }
    detail::require_rows(U, impl_->G.rows() / 3, "QuasiIsometricMetric::apply");
    return detail::deinterleave(impl_->G * detail::interleave(U));
}

VertexField QuasiIsometricMetric::shifted_gradient(const Eigen::SparseMatrix<double>& A, double dt,
                                                   const VertexField& R) {
    constexpr const char* kCaller = "QuasiIsometricMetric::shifted_gradient";
    if (!impl_->ready) {
        throw InvalidInput(std::string(kCaller) + ": update() was not called");
    }
    const Eigen::Index n = impl_->G.rows() / 3;
    detail::require_rows(R, n, kCaller);
    if (A.rows() != n || A.cols() != n) {
        throw InvalidInput(std::string(kCaller) + ": A must be #V×#V");
    }
    if (!detail::finite_at_least(dt, 0)) {
        throw InvalidInput(std::string(kCaller) + ": dt must be non-negative and finite");
    }
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<std::size_t>(3 * A.nonZeros()));
    for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
            for (int c = 0; c < 3; ++c) {
                triplets.emplace_back(3 * static_cast<int>(it.row()) + c,
                                      3 * static_cast<int>(it.col()) + c, dt * it.value());
            }
        }
    }
    Eigen::SparseMatrix<double> shifted(3 * n, 3 * n);
    shifted.setFromTriplets(triplets.begin(), triplets.end());
    shifted += impl_->G;
    shifted.makeCompressed();
    detail::pin_fixed(shifted, impl_->fixed_coordinates);
    impl_->shifted_solver.compute(shifted, kCaller);
    const VertexField rhs = detail::zero_fixed_rows(R, impl_->fixed_vertices);
    return detail::deinterleave(impl_->shifted_solver.solve(detail::interleave(rhs)).col(0));
}

const Eigen::SparseMatrix<double>& QuasiIsometricMetric::matrix() const {
    return impl_->G;
}

const std::vector<std::pair<int, int>>& QuasiIsometricMetric::fake_edges() const {
    return impl_->fake_edges;
}

}  // namespace genflow
