// SPDX-License-Identifier: MIT
#include "genflow/matching/rigid_alignment.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <unordered_map>
#include <vector>

#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/exceptions.h"
#include "genflow/operators/mass_matrix.h"
#include "matching/similarity_scale.h"
#include "operators/triangle.h"

namespace genflow {

Eigen::MatrixX3d Similarity::apply(const Eigen::MatrixX3d& points) const {
    return ((scale * points * rotation.transpose()).rowwise() + translation.transpose());
}

Eigen::Matrix4d Similarity::matrix() const {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topLeftCorner<3, 3>() = scale * rotation;
    m.topRightCorner<3, 1>() = translation;
    return m;
}

namespace {

// Area-weighted samples of a surface: the vertices clustered in a grid of cubes sized for about
// `count` occupied cells (a surface of area A meets about A/c² cubes of side c), each cluster
// replaced by its mass-weighted mean with the summed mass.
struct Samples {
    Eigen::MatrixX3d points;
    Eigen::VectorXd masses;
    double spacing = 0;  // the cube side
};

Samples cluster(const TriangleMesh& mesh, int count) {
    const Eigen::VectorXd masses = lumped_masses(mesh, MassType::Barycentric);
    const double area = masses.sum();
    const double side = std::sqrt(area / count);
    const Eigen::RowVector3d origin = mesh.V.colwise().minCoeff();
    std::unordered_map<std::int64_t, Eigen::Index> cell_of;
    std::vector<Eigen::Vector4d> sums;  // Σm·x, Σm
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        if (!(masses[i] > 0)) {
            continue;
        }
        const Eigen::Array3d cell = ((mesh.V.row(i) - origin) / side).array().floor().transpose();
        const std::int64_t key =
            (static_cast<std::int64_t>(cell.x()) * 2097152 + static_cast<std::int64_t>(cell.y())) *
                2097152 +
            static_cast<std::int64_t>(cell.z());
        const auto [it, inserted] =
            cell_of.try_emplace(key, static_cast<Eigen::Index>(sums.size()));
        if (inserted) {
            sums.emplace_back(Eigen::Vector4d::Zero());
        }
        sums[static_cast<std::size_t>(it->second)].head<3>() +=
            masses[i] * mesh.V.row(i).transpose();
        sums[static_cast<std::size_t>(it->second)][3] += masses[i];
    }
    Samples samples{Eigen::MatrixX3d(static_cast<Eigen::Index>(sums.size()), 3),
                    Eigen::VectorXd(static_cast<Eigen::Index>(sums.size())), side};
    for (std::size_t k = 0; k < sums.size(); ++k) {
        const auto row = static_cast<Eigen::Index>(k);
        samples.points.row(row) = (sums[k].head<3>() / sums[k][3]).transpose();
        samples.masses[row] = sums[k][3];
    }
    return samples;
}

struct Frame {
    Eigen::Vector3d centre;
    Eigen::Matrix3d axes;  // principal axes as columns
    double radius;         // RMS distance to the centre
};

Frame principal_frame(const Samples& s) {
    const double total = s.masses.sum();
    const Eigen::Vector3d centre = (s.masses.transpose() * s.points).transpose() / total;
    const Eigen::MatrixX3d centred = s.points.rowwise() - centre.transpose();
    const Eigen::Matrix3d covariance =
        centred.transpose() * s.masses.asDiagonal() * centred / total;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
    return {centre, eigen.eigenvectors(), std::sqrt(std::max(covariance.trace(), 1e-300))};
}

constexpr double kDistinctAngle = 0.5236;  // 30°

// A start and its rigid flow.
struct Candidate {
    Similarity transform;
    double value = std::numeric_limits<double>::infinity();
    double step = 0;  // last accepted step size
};

class RigidFlow {
public:
    RigidFlow(const Samples& moving, const Samples& fixed, const RigidAlignmentOptions& options,
              double max_displacement)
        : moving_(moving),
          fixed_(fixed),
          options_{.alpha = options.alpha,
                   .epsilon = fixed.spacing,
                   .truncation = 1e-4,
                   .weights = HausdorffWeights::Normalized,
                   .moving_coverage = options.moving_coverage},
          scaling_(false),
          stagnation_(options.stagnation_tolerance),
          max_displacement_(max_displacement) {}

    double value(const Similarity& t) const {
        return pseudo_hausdorff(t.apply(moving_.points), moving_.masses, fixed_.points,
                                fixed_.masses, options_)
            .value;
    }

    // Up to `iterations` Armijo steps of the flow restricted to similarities.
    void run(Candidate& c, int iterations) const {
        double reference = std::numeric_limits<double>::infinity();  // value 10 steps ago
        for (int k = 0; k < iterations; ++k) {
            if (k % 10 == 0) {
                // (Both finite: inf − inf would raise FE_INVALID.)
                if (std::isfinite(reference) && std::isfinite(c.value) &&
                    reference - c.value <= stagnation_ * std::abs(c.value)) {
                    return;
                }
                reference = c.value;
            }
            const Eigen::MatrixX3d Z = c.transform.apply(moving_.points);
            const PseudoHausdorffEvaluation e =
                pseudo_hausdorff(Z, moving_.masses, fixed_.points, fixed_.masses, options_);
            c.value = e.value;
            // The rigid (and scaling) fields at Z about its M-centroid; the M-projected
            // gradient's coefficients δ solve (JᵀMJ) δ = Jᵀ dE.
            const double total = moving_.masses.sum();
            const Eigen::Vector3d centre = (moving_.masses.transpose() * Z).transpose() / total;
            const int fields = scaling_ ? 7 : 6;
            Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(fields, fields);
            Eigen::VectorXd rhs = Eigen::VectorXd::Zero(fields);
            Eigen::Matrix<double, 3, Eigen::Dynamic> J(3, fields);
            for (Eigen::Index i = 0; i < Z.rows(); ++i) {
                const Eigen::Vector3d y = Z.row(i).transpose() - centre;
                J.leftCols<3>().setIdentity();
                J.block<3, 3>(0, 3) << 0, y.z(), -y.y(), -y.z(), 0, y.x(), y.y(), -y.x(), 0;
                if (scaling_) {
                    J.col(6) = y;
                }
                gram += moving_.masses[i] / total * J.transpose() * J;
                rhs += J.transpose() * e.differential.row(i).transpose();
            }
            const Eigen::VectorXd delta = gram.fullPivLu().solve(rhs);
            const double slope = rhs.dot(delta);
            if (!(slope > 0) || !delta.allFinite()) {
                return;
            }
            double largest = 0;  // the largest vertex speed of the field J δ
            for (Eigen::Index i = 0; i < Z.rows(); ++i) {
                const Eigen::Vector3d y = Z.row(i).transpose() - centre;
                Eigen::Vector3d v = delta.head<3>() + delta.segment<3>(3).cross(y);
                if (scaling_) {
                    v += delta[6] * y;
                }
                largest = std::max(largest, v.norm());
            }
            const double cap = max_displacement_ / largest;
            double tau = c.step > 0 ? std::min(2 * c.step, cap) : cap;
            bool accepted = false;
            for (int halving = 0; halving < 30 && !accepted; ++halving, tau /= 2) {
                const Similarity trial = moved(c.transform, centre, delta, tau);
                const double v = value(trial);
                if (v <= c.value - 1e-4 * tau * slope) {
                    c.transform = trial;
                    c.value = v;
                    c.step = tau;
                    accepted = true;
                }
            }
            if (!accepted) {
                return;
            }
        }
    }

private:
    // The similarity after the finite motion z ↦ c + e^{−τσ} Q (z − c) − τ t_δ, Q the rotation
    // by −τ ω (exact rotations, so the shape never shears).
    Similarity moved(const Similarity& t, const Eigen::Vector3d& centre,
                     const Eigen::VectorXd& delta, double tau) const {
        const Eigen::Vector3d omega = -tau * delta.segment<3>(3);
        const double angle = omega.norm();
        const Eigen::Matrix3d Q = angle > 0
                                      ? Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix()
                                      : Eigen::Matrix3d::Identity();
        const double grow = scaling_ ? std::exp(-tau * delta[6]) : 1.0;
        Similarity result;
        result.scale = grow * t.scale;
        result.rotation = Q * t.rotation;
        result.translation = grow * Q * (t.translation - centre) + centre - tau * delta.head<3>();
        return result;
    }

    const Samples& moving_;
    const Samples& fixed_;
    PseudoHausdorffOptions options_;
    bool scaling_;
    double stagnation_;
    double max_displacement_;
};

}  // namespace

std::vector<RigidAlignment> rigid_alignment_candidates(const TriangleMesh& moving,
                                                       const TriangleMesh& fixed,
                                                       const RigidAlignmentOptions& options) {
    for (const TriangleMesh* mesh : {&moving, &fixed}) {
        detail::require_valid_mesh(*mesh, "align_rigidly");
        if (mesh->F.rows() == 0) {
            throw InvalidInput("align_rigidly: a mesh has no faces");
        }
    }
    if (options.samples < 8 || options.start_iterations < 0 || options.refine_iterations < 0 ||
        options.best_starts < 1 || !detail::finite_at_least(options.alpha, 0.5) ||
        !detail::finite_at_least(options.stagnation_tolerance, 0) ||
        !(options.moving_coverage >= 0 && options.moving_coverage <= 1)) {
        throw InvalidInput(
            "align_rigidly: need samples >= 8, iterations >= 0, best_starts >= 1, alpha >= 0.5, "
            "moving_coverage in [0, 1]");
    }
    const Samples a = cluster(moving, options.samples);
    const Samples b = cluster(fixed, options.samples);
    if (a.points.rows() == 0 || b.points.rows() == 0) {
        throw InvalidInput("align_rigidly: a mesh has zero area");
    }
    // The scale from the areas: unlike sizes or principal radii, area does not change with the
    // pose of an articulated or near-isometric shape. From the volumes where the areas mislead
    // (a rough surface: similarity_scale.h).
    double scale = 1;
    if (options.allow_scaling) {
        scale = std::sqrt(b.masses.sum() / a.masses.sum());
        scale = detail::volume_scale_where_areas_mislead(moving, fixed, scale).value_or(scale);
    }
    const Frame fa = principal_frame(a);
    const Frame fb = principal_frame(b);
    const double diagonal = (b.points.colwise().maxCoeff() - b.points.colwise().minCoeff()).norm();
    const RigidFlow flow(a, b, options, 0.05 * diagonal);

    // The 24 proper rotations taking a's principal axes onto b's, in every order and sign.
    std::vector<Candidate> candidates;
    std::array<int, 3> order{0, 1, 2};
    do {
        for (int signs = 0; signs < 8; ++signs) {
            Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
            for (int r = 0; r < 3; ++r) {
                P(r, order[static_cast<std::size_t>(r)]) = (signs >> r & 1) != 0 ? -1.0 : 1.0;
            }
            const Eigen::Matrix3d R = fb.axes * P * fa.axes.transpose();
            if (R.determinant() < 0) {
                continue;
            }
            Candidate c;
            c.transform.rotation = R;
            c.transform.scale = scale;
            c.transform.translation = fb.centre - c.transform.scale * R * fa.centre;
            candidates.push_back(c);
        }
    } while (std::next_permutation(order.begin(), order.end()));

    // The starts are independent: one per thread (each flow is too small to split).
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        flow.run(candidates[k], options.start_iterations);
        candidates[k].value = flow.value(candidates[k].transform);
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& x, const Candidate& y) { return x.value < y.value; });
    // The best starts whose rotations differ by at least 30° from every better one (others
    // are the same optimum reached twice), refined, and deduplicated again (two starts may
    // meet in one optimum).
    const auto distinct = [&](const std::vector<Candidate>& sorted, std::size_t count) {
        std::vector<Candidate> kept;
        for (const Candidate& c : sorted) {
            const bool repeated = std::any_of(kept.begin(), kept.end(), [&](const Candidate& d) {
                return Eigen::AngleAxisd(c.transform.rotation * d.transform.rotation.transpose())
                           .angle() < kDistinctAngle;
            });
            if (!repeated) {
                kept.push_back(c);
            }
            if (kept.size() == count) {
                break;
            }
        }
        return kept;
    };
    std::vector<Candidate> refined =
        distinct(candidates, static_cast<std::size_t>(options.best_starts));
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t k = 0; k < refined.size(); ++k) {
        flow.run(refined[k], options.refine_iterations);
        refined[k].value = flow.value(refined[k].transform);
    }
    std::sort(refined.begin(), refined.end(),
              [](const Candidate& x, const Candidate& y) { return x.value < y.value; });
    refined = distinct(refined, refined.size());
    std::vector<RigidAlignment> result;
    for (const Candidate& c : refined) {
        result.push_back({c.transform, c.value});
    }
    return result;
}

RigidAlignment align_rigidly(const TriangleMesh& moving, const TriangleMesh& fixed,
                             const RigidAlignmentOptions& options) {
    return rigid_alignment_candidates(moving, fixed, options).front();
}

}  // namespace genflow
