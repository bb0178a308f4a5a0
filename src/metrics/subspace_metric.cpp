// SPDX-License-Identifier: MIT
#include "genflow/metrics/subspace_metric.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <string>

#include "genflow/exceptions.h"
#include "metrics/metric_support.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

// √m_i repeated for the three rows of vertex i.
Eigen::VectorXd row_sqrt_masses(const Eigen::VectorXd& masses) {
    Eigen::VectorXd s(3 * masses.size());
    for (Eigen::Index i = 0; i < masses.size(); ++i) {
        s.segment<3>(3 * i).setConstant(std::sqrt(masses[i]));
    }
    return s;
}

// Block Gram–Schmidt in the M inner product (SPEC.md §6), done on B̃ = M^{1/2} B where it is
// the plain inner product: each block minus its components along the earlier ones (twice,
// for round-off), then an eigen-decomposition of its Gram matrix drops the directions
// already spanned (eigenvalues below 1e-8 of the block's own largest before projection) and
// orthonormalizes the rest. Returns the Q̃_k = M^{1/2} Q_k.
std::vector<FieldBlock> orthonormalize(const std::vector<FieldBlock>& blocks,
                                       const Eigen::VectorXd& sqrt_mass) {
    std::vector<FieldBlock> result;
    for (const FieldBlock& block : blocks) {
        if (block.fields.cols() == 0) {
            continue;
        }
        Eigen::MatrixXd B = block.fields.array().colwise() * sqrt_mass.array();
        const Eigen::MatrixXd original_gram = B.transpose() * B;
        const double scale =
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(original_gram, Eigen::EigenvaluesOnly)
                .eigenvalues()
                .maxCoeff();
        if (!(scale > 0)) {
            continue;
        }
        for (int pass = 0; pass < 2; ++pass) {
            for (const FieldBlock& earlier : result) {
                B.noalias() -= earlier.fields * (earlier.fields.transpose() * B);
            }
        }
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(B.transpose() * B);
        std::vector<Eigen::Index> kept;
        for (Eigen::Index k = 0; k < eigen.eigenvalues().size(); ++k) {
            if (eigen.eigenvalues()[k] > 1e-8 * scale) {
                kept.push_back(k);
            }
        }
        if (kept.empty()) {
            continue;
        }
        Eigen::MatrixXd directions(B.cols(), static_cast<Eigen::Index>(kept.size()));
        for (std::size_t c = 0; c < kept.size(); ++c) {
            directions.col(static_cast<Eigen::Index>(c)) =
                eigen.eigenvectors().col(kept[c]) / std::sqrt(eigen.eigenvalues()[kept[c]]);
        }
        result.push_back({B * directions, block.penalty});
    }
    return result;
}

}  // namespace

std::vector<FieldBlock> SubspaceMetric::orthonormal_blocks() const {
    std::vector<FieldBlock> blocks = blocks_;
    for (FieldBlock& block : blocks) {
        block.fields = block.fields.array().colwise() / sqrt_mass_.array();
    }
    return blocks;
}

SubspaceMetric::SubspaceMetric(FieldBasis basis, SubspaceOptions options)
    : basis_(std::move(basis)), options_(options) {
    if (!basis_) {
        throw InvalidInput("SubspaceMetric: no basis given");
    }
}

void SubspaceMetric::update(const TriangleMesh& mesh) {
    detail::require_valid_mesh(mesh, "SubspaceMetric::update");
    detail::require_mask_size(fixed_, mesh.V.rows(), "SubspaceMetric::update");
    for (const bool fixed : fixed_) {
        if (fixed) {
            throw InvalidInput("SubspaceMetric::update: fixed vertices are not supported");
        }
    }
    Eigen::VectorXd masses = detail::floored_lumped_masses(mesh, options_.mass);
    std::vector<FieldBlock> blocks = basis_(mesh, masses);
    for (const FieldBlock& block : blocks) {
        if (block.fields.rows() != 3 * mesh.V.rows()) {
            throw InvalidInput("SubspaceMetric::update: a block has " +
                               std::to_string(block.fields.rows()) + " rows for " +
                               std::to_string(mesh.V.rows()) + " vertices (3 per vertex needed)");
        }
        if (!detail::all_finite(block.fields) || !detail::finite_above(block.penalty, 0)) {
            throw InvalidInput(
                "SubspaceMetric::update: block fields must be finite and penalties positive");
        }
    }
    sqrt_mass_ = row_sqrt_masses(masses);
    blocks_ = orthonormalize(blocks, sqrt_mass_);
    masses_ = std::move(masses);
}

VertexField SubspaceMetric::gradient(const VertexField& dEdX) const {
    detail::require_rows(dEdX, masses_.size(), "SubspaceMetric::gradient");
    // G⁻¹d = M⁻¹d + Σ (1/μ − 1) M^{-1/2} Q̃ Q̃ᵀ M^{-1/2} d.
    const Eigen::VectorXd r = detail::interleave(dEdX).cwiseQuotient(sqrt_mass_);
    Eigen::VectorXd g = r;
    for (const FieldBlock& block : blocks_) {
        g += (1 / block.penalty - 1) * (block.fields * (block.fields.transpose() * r));
    }
    return detail::deinterleave(g.cwiseQuotient(sqrt_mass_));
}

VertexField SubspaceMetric::apply(const VertexField& U) const {
    detail::require_rows(U, masses_.size(), "SubspaceMetric::apply");
    // G u = M u + Σ (μ − 1) M^{1/2} Q̃ Q̃ᵀ M^{1/2} u.
    const Eigen::VectorXd r = detail::interleave(U).cwiseProduct(sqrt_mass_);
    Eigen::VectorXd result = r;
    for (const FieldBlock& block : blocks_) {
        result += (block.penalty - 1) * (block.fields * (block.fields.transpose() * r));
    }
    return detail::deinterleave(result.cwiseProduct(sqrt_mass_));
}

VertexField SubspaceMetric::shifted_gradient(const Eigen::SparseMatrix<double>& A, double dt,
                                             const VertexField& R) {
    detail::require_rows(R, masses_.size(), "SubspaceMetric::shifted_gradient");
    const Eigen::Index n = masses_.size();
    if (A.rows() != n || A.cols() != n) {
        throw InvalidInput("SubspaceMetric::shifted_gradient: A must be #V×#V");
    }
    if (!detail::finite_at_least(dt, 0)) {
        throw InvalidInput("SubspaceMetric::shifted_gradient: dt must be finite and >= 0");
    }
    // E = M + dt·A, diagonal.
    Eigen::VectorXd E = masses_;
    for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
            if (it.row() != it.col() && it.value() != 0) {
                throw InvalidInput("SubspaceMetric::shifted_gradient: A must be diagonal");
            }
            if (it.row() == it.col()) {
                E[it.row()] += dt * it.value();
            }
        }
    }
    if (!(E.minCoeff() > 0) || !detail::all_finite(E)) {
        throw SolverError("SubspaceMetric::shifted_gradient: M + dt·A is not positive");
    }
    Eigen::VectorXd E_rows(3 * n);  // E for each of the 3n rows
    for (Eigen::Index i = 0; i < n; ++i) {
        E_rows.segment<3>(3 * i).setConstant(E[i]);
    }
    const auto E_inverse_times = [&](const Eigen::MatrixXd& fields) -> Eigen::MatrixXd {
        return fields.array().colwise() / E_rows.array();
    };
    // Woodbury: (E + UΓUᵀ)⁻¹r = E⁻¹r − E⁻¹U (Γ⁻¹ + UᵀE⁻¹U)⁻¹ UᵀE⁻¹r; neutral blocks drop out.
    Eigen::Index columns = 0;
    for (const FieldBlock& block : blocks_) {
        columns += block.penalty != 1 ? block.fields.cols() : 0;
    }
    Eigen::MatrixXd U(3 * n, columns);
    Eigen::VectorXd gamma_inverse(columns);
    Eigen::Index column = 0;
    for (const FieldBlock& block : blocks_) {
        if (block.penalty != 1) {
            U.middleCols(column, block.fields.cols()) =
                block.fields.array().colwise() * sqrt_mass_.array();  // M Q = M^{1/2} Q̃
            gamma_inverse.segment(column, block.fields.cols()).setConstant(1 / (block.penalty - 1));
            column += block.fields.cols();
        }
    }
    const Eigen::VectorXd Er = E_inverse_times(detail::interleave(R));
    if (columns == 0) {
        return detail::deinterleave(Er);
    }
    const Eigen::MatrixXd EU = E_inverse_times(U);
    Eigen::MatrixXd capacitance = U.transpose() * EU;
    capacitance.diagonal() += gamma_inverse;
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(capacitance);
    if (!lu.isInvertible()) {
        throw SolverError("SubspaceMetric::shifted_gradient: singular Woodbury system");
    }
    const Eigen::VectorXd result = Er - EU * lu.solve(U.transpose() * Er);
    if (!detail::all_finite(result)) {
        throw SolverError("SubspaceMetric::shifted_gradient: non-finite solution");
    }
    return detail::deinterleave(result);
}

std::vector<FieldBlock> rigid_motion_blocks(const TriangleMesh& mesh, const Eigen::VectorXd& masses,
                                            const QuasiRigidOptions& options) {
    const Eigen::Index n = mesh.V.rows();
    const Eigen::RowVector3d centre =
        (masses.transpose() * mesh.V) / std::max(masses.sum(), 1e-300);
    FieldBlock translation{Eigen::MatrixXd::Zero(3 * n, 3), options.translation};
    FieldBlock rotation{Eigen::MatrixXd::Zero(3 * n, 3), options.rotation};
    FieldBlock scaling{Eigen::MatrixXd::Zero(3 * n, 1), options.scaling};
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Vector3d y = (mesh.V.row(i) - centre).transpose();
        translation.fields.block<3, 3>(3 * i, 0).setIdentity();
        // Column a: e_a × y.
        rotation.fields.block<3, 3>(3 * i, 0) << 0, y.z(), -y.y(),  //
            -y.z(), 0, y.x(),                                       //
            y.y(), -y.x(), 0;
        scaling.fields.block<3, 1>(3 * i, 0) = y;
    }
    return {std::move(translation), std::move(rotation), std::move(scaling)};
}

SubspaceMetric quasi_rigid_metric(const QuasiRigidOptions& options) {
    for (const double penalty : {options.translation, options.rotation, options.scaling}) {
        if (!detail::finite_above(penalty, 0)) {
            throw InvalidInput("quasi_rigid_metric: penalties must be positive and finite");
        }
    }
    return SubspaceMetric(
        [options](const TriangleMesh& mesh, const Eigen::VectorXd& masses) {
            return rigid_motion_blocks(mesh, masses, options);
        },
        {options.mass});
}

}  // namespace genflow
