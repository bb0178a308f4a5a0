// SPDX-License-Identifier: MIT
#include "genflow/metrics/subspace_metric.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "genflow/exceptions.h"
#include "metrics/metric_support.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

// m_i repeated for the three rows of vertex i.
Eigen::VectorXd row_masses(const Eigen::VectorXd& masses) {
    Eigen::VectorXd m(3 * masses.size());
    for (Eigen::Index i = 0; i < masses.size(); ++i) {
        m.segment<3>(3 * i).setConstant(masses[i]);
    }
    return m;
}

// Each 3n-row column of X as a #V×3 field, `op` applied, and back.
template <class Op>
Eigen::MatrixXd column_by_column(const Eigen::MatrixXd& X, const Op& op) {
    Eigen::MatrixXd result(X.rows(), X.cols());
    for (Eigen::Index c = 0; c < X.cols(); ++c) {
        result.col(c) = detail::interleave(op(detail::deinterleave(X.col(c))));
    }
    return result;
}

}  // namespace

Eigen::MatrixXd SubspaceMetric::base_times(const Eigen::MatrixXd& X) const {
    if (!base_) {
        return X.array().colwise() * row_masses_.array();
    }
    return column_by_column(X, [&](const VertexField& field) { return base_->apply(field); });
}

Eigen::VectorXd SubspaceMetric::base_inverse_times(const Eigen::VectorXd& x) const {
    if (!base_) {
        return x.cwiseQuotient(row_masses_);
    }
    return detail::interleave(base_->gradient(detail::deinterleave(x)));
}

SubspaceMetric::SubspaceMetric(FieldBasis basis, SubspaceOptions options,
                               std::unique_ptr<Metric> base)
    : basis_(std::move(basis)), options_(options), base_(std::move(base)) {
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
    // Until this update has ended the metric has no vertices, and refuses every field: one
    // that threw half-way must not pair the fields of one update with the weights of another.
    masses_.resize(0);
    Eigen::VectorXd masses = detail::floored_lumped_masses(mesh, options_.mass);
    const std::vector<FieldBlock> blocks = basis_(mesh, masses);
    Eigen::Index columns = 0;
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
        columns += block.fields.cols();
    }
    if (base_) {
        base_->update(mesh);
    }
    row_masses_ = row_masses(masses);

    // All fields side by side, F = [F_1 … F_K], and their Gram matrix C = Fᵀ B F.
    Eigen::MatrixXd fields(3 * mesh.V.rows(), columns);
    std::vector<Eigen::Index> first_column;
    Eigen::Index column = 0;
    for (const FieldBlock& block : blocks) {
        first_column.push_back(column);
        fields.middleCols(column, block.fields.cols()) = block.fields;
        column += block.fields.cols();
    }
    // C = Fᵀ B F: for B = M, half of it as (M^½ F)ᵀ (M^½ F), a symmetric rank update.
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(columns, columns);
    if (!base_) {
        const Eigen::MatrixXd scaled = fields.array().colwise() * row_masses_.array().sqrt();
        gram.selfadjointView<Eigen::Lower>().rankUpdate(scaled.transpose());
        gram.triangularView<Eigen::StrictlyUpper>() = gram.transpose();
    } else {
        gram.noalias() = fields.transpose() * base_times(fields);
        gram = (gram + gram.transpose()) / 2;
    }

    // Block Gram–Schmidt in the B inner product (docs/formulas.md §6): each block minus its
    // components along the earlier ones (twice, for round-off), then an eigen-decomposition of its
    // Gram matrix drops the directions already spanned (eigenvalues below 1e-8 of the block's own
    // largest before projection) and orthonormalizes the rest. It runs on the coefficients
    // Q_k = F T_k, where every inner product is one of C: (B Q_k)ᵀ F S = T_kᵀ C S. Projecting
    // the 3n-row fields instead costs four products of O(n·m²), most of a match with many
    // fields (docs/benchmarks.md, "Subspace metric"). C's rounding,
    // magnified by nearly repeated fields, leaves the blocks of a 17-part chain orthonormal to
    // 3e-10 (tests/matching/matching_test.cpp).
    std::vector<CoefficientBlock> coefficients;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        const Eigen::Index width = blocks[b].fields.cols();
        if (width == 0) {
            continue;
        }
        const Eigen::MatrixXd own = gram.block(first_column[b], first_column[b], width, width);
        const double scale =
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(own, Eigen::EigenvaluesOnly)
                .eigenvalues()
                .maxCoeff();
        if (!(scale > 0)) {
            continue;
        }
        // Coefficients of the blocks up to b only: the rows after them stay zero.
        const Eigen::Index end = first_column[b] + width;
        Eigen::MatrixXd S = Eigen::MatrixXd::Zero(end, width);
        S.bottomRows(width).setIdentity();
        for (int pass = 0; pass < 2; ++pass) {
            for (const CoefficientBlock& earlier : coefficients) {
                const Eigen::Index rows = earlier.T.rows();
                const Eigen::MatrixXd components =
                    earlier.T.transpose() * (gram.block(0, 0, rows, end) * S);
                S.topRows(rows).noalias() -= earlier.T * components;
            }
        }
        Eigen::MatrixXd projected_gram = S.transpose() * gram.topLeftCorner(end, end) * S;
        projected_gram = (projected_gram + projected_gram.transpose()) / 2;
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(projected_gram);
        std::vector<Eigen::Index> kept;
        for (Eigen::Index k = 0; k < eigen.eigenvalues().size(); ++k) {
            if (eigen.eigenvalues()[k] > 1e-8 * scale) {
                kept.push_back(k);
            }
        }
        if (kept.empty()) {
            continue;
        }
        Eigen::MatrixXd directions(width, static_cast<Eigen::Index>(kept.size()));
        for (std::size_t c = 0; c < kept.size(); ++c) {
            directions.col(static_cast<Eigen::Index>(c)) =
                eigen.eigenvectors().col(kept[c]) / std::sqrt(eigen.eigenvalues()[kept[c]]);
        }
        coefficients.push_back({S * directions, blocks[b].penalty});
    }
    // G⁻¹ and G as F W Fᵀ and BF W' (BF)ᵀ corrections: W = Σ (1/μ_k − 1) T_k T_kᵀ and
    // W' = Σ (μ_k − 1) T_k T_kᵀ, m×m.
    Eigen::MatrixXd gradient_weights = Eigen::MatrixXd::Zero(columns, columns);
    Eigen::MatrixXd apply_weights = Eigen::MatrixXd::Zero(columns, columns);
    for (const CoefficientBlock& block : coefficients) {
        const Eigen::Index rows = block.T.rows();
        const Eigen::MatrixXd outer = block.T * block.T.transpose();
        gradient_weights.topLeftCorner(rows, rows) += (1 / block.penalty - 1) * outer;
        apply_weights.topLeftCorner(rows, rows) += (block.penalty - 1) * outer;
    }
    fields_ = std::move(fields);
    coefficients_ = std::move(coefficients);
    gradient_weights_ = std::move(gradient_weights);
    apply_weights_ = std::move(apply_weights);
    masses_ = std::move(masses);
}

std::vector<FieldBlock> SubspaceMetric::orthonormal_blocks() const {
    std::vector<FieldBlock> blocks;
    for (const CoefficientBlock& block : coefficients_) {
        blocks.push_back({fields_.leftCols(block.T.rows()) * block.T, block.penalty});
    }
    return blocks;
}

VertexField SubspaceMetric::gradient(const VertexField& dEdX) const {
    detail::require_rows(dEdX, masses_.size(), "SubspaceMetric::gradient");
    // G⁻¹d = B⁻¹d + Σ (1/μ − 1) Q Qᵀ d = B⁻¹d + F W Fᵀ d.
    const Eigen::VectorXd d = detail::interleave(dEdX);
    Eigen::VectorXd g = base_inverse_times(d);
    if (fields_.cols() > 0) {
        const Eigen::VectorXd components = fields_.transpose() * d;
        g.noalias() += fields_ * (gradient_weights_ * components);
    }
    return detail::deinterleave(g);
}

VertexField SubspaceMetric::apply(const VertexField& U) const {
    detail::require_rows(U, masses_.size(), "SubspaceMetric::apply");
    // G u = B u + Σ (μ − 1) BQ (BQ)ᵀ u = B (u + F W' Fᵀ B u): B is symmetric, and the flows,
    // which only call gradient(), need not keep B F.
    const Eigen::VectorXd u = detail::interleave(U);
    const Eigen::VectorXd Bu = base_times(u);
    if (fields_.cols() == 0) {
        return detail::deinterleave(Bu);
    }
    const Eigen::VectorXd components = fields_.transpose() * Bu;
    return detail::deinterleave(base_times(u + fields_ * (apply_weights_ * components)));
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
    // dt·A's diagonal, which is all of it.
    Eigen::VectorXd shift = Eigen::VectorXd::Zero(n);
    for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
            if (it.row() != it.col() && it.value() != 0) {
                throw InvalidInput("SubspaceMetric::shifted_gradient: A must be diagonal");
            }
            if (it.row() == it.col()) {
                shift[it.row()] += dt * it.value();
            }
        }
    }
    // E⁻¹ X for E = B + dt·A: diagonal for B = M, else the base's own shifted solve.
    std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> E_inverse_times;
    if (!base_) {
        const Eigen::VectorXd E = masses_ + shift;
        if (!(E.minCoeff() > 0) || !detail::all_finite(E)) {
            throw SolverError("SubspaceMetric::shifted_gradient: M + dt·A is not positive");
        }
        E_inverse_times = [E_rows = row_masses(E)](const Eigen::MatrixXd& X) -> Eigen::MatrixXd {
            return X.array().colwise() / E_rows.array();
        };
    } else {
        E_inverse_times = [&](const Eigen::MatrixXd& X) {
            return column_by_column(
                X, [&](const VertexField& field) { return base_->shifted_gradient(A, dt, field); });
        };
    }
    // Woodbury: (E + UΓUᵀ)⁻¹r = E⁻¹r − E⁻¹U (Γ⁻¹ + UᵀE⁻¹U)⁻¹ UᵀE⁻¹r; neutral blocks drop out.
    Eigen::Index columns = 0;
    for (const CoefficientBlock& block : coefficients_) {
        columns += block.penalty != 1 ? block.T.cols() : 0;
    }
    Eigen::MatrixXd T(fields_.cols(), columns);  // U = B F T
    Eigen::VectorXd gamma_inverse(columns);
    Eigen::Index column = 0;
    for (const CoefficientBlock& block : coefficients_) {
        if (block.penalty != 1) {
            T.middleCols(column, block.T.cols()) << block.T,
                Eigen::MatrixXd::Zero(T.rows() - block.T.rows(), block.T.cols());
            gamma_inverse.segment(column, block.T.cols()).setConstant(1 / (block.penalty - 1));
            column += block.T.cols();
        }
    }
    const Eigen::VectorXd Er = E_inverse_times(detail::interleave(R));
    if (columns == 0) {
        return detail::deinterleave(Er);
    }
    const Eigen::MatrixXd U = base_times(fields_ * T);
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
