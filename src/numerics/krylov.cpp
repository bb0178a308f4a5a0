// SPDX-License-Identifier: MIT
#include "numerics/krylov.h"

#include <Eigen/Dense>
#include <cmath>
#include <utility>
#include <vector>

namespace genflow::detail {

KrylovResult conjugate_gradient(const LinearOperator& A, const Eigen::VectorXd& b,
                                const Eigen::VectorXd& x0, double tolerance, int max_iterations) {
    KrylovResult result;
    result.x = x0;
    const double b_norm = b.norm();
    if (b_norm == 0) {
        result.x.setZero();
        result.converged = true;
        return result;
    }
    Eigen::VectorXd r = b - A(result.x);
    Eigen::VectorXd p = r;
    double rr = r.squaredNorm();
    while (std::sqrt(rr) > tolerance * b_norm && result.iterations < max_iterations) {
        const Eigen::VectorXd Ap = A(p);
        const double pAp = p.dot(Ap);
        if (!std::isfinite(pAp) || pAp <= 0) {
            break;  // not positive definite (or breakdown): report non-convergence
        }
        const double alpha = rr / pAp;
        result.x += alpha * p;
        r -= alpha * Ap;
        const double rr_next = r.squaredNorm();
        p = r + (rr_next / rr) * p;
        rr = rr_next;
        ++result.iterations;
    }
    result.relative_residual = std::sqrt(rr) / b_norm;
    result.converged = result.relative_residual <= tolerance;
    return result;
}

namespace {

// Restarted GMRES with right preconditioning. `apply(v, image)` returns A·v and, when the images
// are kept (`image` not null), C·v in its second argument; `image` then receives C·x, and x0
// must be zero (its image is then zero without an application).
template <class Apply>
KrylovResult restarted_gmres(const Apply& apply, const LinearOperator& P, const Eigen::VectorXd& b,
                             const Eigen::VectorXd& x0, double tolerance, int restart,
                             int max_iterations, Eigen::MatrixXd* image) {
    KrylovResult result;
    result.x = x0;
    Eigen::MatrixXd scratch;
    const double b_norm = b.norm();
    if (b_norm == 0) {
        result.x.setZero();
        result.converged = true;
        return result;
    }
    bool x_is_zero = image != nullptr;
    const Eigen::Index n = b.size();
    const int m = std::max(1, restart);
    while (result.iterations < max_iterations) {
        const Eigen::VectorXd r = x_is_zero ? b : (b - apply(result.x, scratch)).eval();
        if (image != nullptr && !x_is_zero) {
            *image = scratch;  // C·x anew at a restart
        }
        const double beta = r.norm();
        result.relative_residual = beta / b_norm;
        if (result.relative_residual <= tolerance) {
            result.converged = true;
            return result;
        }
        // Arnoldi on A·P with modified Gram–Schmidt; Givens rotations keep the least-squares
        // problem triangular so the residual norm is known at every inner step. The basis V
        // and its preconditioned images Z = P V (kept, so that the update Z y needs no further
        // P) grow a vector at a time: a solve that converges in a few iterations touches only
        // those, not m + 1 columns of the system's size.
        std::vector<Eigen::VectorXd> V{r / beta};
        std::vector<Eigen::VectorXd> Z;
        std::vector<Eigen::MatrixXd> images;  // C·Z, when kept
        V.reserve(static_cast<std::size_t>(m) + 1);
        Z.reserve(static_cast<std::size_t>(m));
        Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m + 1, m);
        Eigen::VectorXd cs = Eigen::VectorXd::Zero(m);
        Eigen::VectorXd sn = Eigen::VectorXd::Zero(m);
        Eigen::VectorXd g = Eigen::VectorXd::Zero(m + 1);
        g[0] = beta;
        int k = 0;
        bool estimate_converged = false;
        for (; k < m && result.iterations < max_iterations; ++k) {
            Z.push_back(P(V[static_cast<std::size_t>(k)]));
            Eigen::VectorXd w = apply(Z.back(), scratch);
            if (image != nullptr) {
                images.push_back(std::move(scratch));  // the next application refills it
            }
            for (int j = 0; j <= k; ++j) {
                H(j, k) = w.dot(V[static_cast<std::size_t>(j)]);
                w -= H(j, k) * V[static_cast<std::size_t>(j)];
            }
            H(k + 1, k) = w.norm();
            V.push_back(H(k + 1, k) > 0 ? (w / H(k + 1, k)).eval() : Eigen::VectorXd::Zero(n));
            for (int j = 0; j < k; ++j) {
                const double t = cs[j] * H(j, k) + sn[j] * H(j + 1, k);
                H(j + 1, k) = -sn[j] * H(j, k) + cs[j] * H(j + 1, k);
                H(j, k) = t;
            }
            const double denominator = std::hypot(H(k, k), H(k + 1, k));
            cs[k] = denominator > 0 ? H(k, k) / denominator : 1.0;
            sn[k] = denominator > 0 ? H(k + 1, k) / denominator : 0.0;
            H(k, k) = denominator;
            H(k + 1, k) = 0;
            g[k + 1] = -sn[k] * g[k];
            g[k] = cs[k] * g[k];
            ++result.iterations;
            estimate_converged = std::abs(g[k + 1]) <= tolerance * b_norm;
            if (estimate_converged || denominator == 0) {
                ++k;
                break;
            }
        }
        const Eigen::VectorXd y =
            H.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
        for (int j = 0; j < k; ++j) {
            result.x += y[j] * Z[static_cast<std::size_t>(j)];
        }
        if (image != nullptr) {
            for (int j = 0; j < k; ++j) {
                const Eigen::MatrixXd& term = images[static_cast<std::size_t>(j)];
                if (x_is_zero && j == 0) {
                    *image = y[j] * term;
                } else {
                    *image += y[j] * term;
                }
            }
        }
        x_is_zero = false;
        // The rotated right-hand side's last entry is the residual norm (in exact arithmetic,
        // and to rounding with modified Gram–Schmidt over one cycle): trusted, it saves the
        // product that would only confirm it.
        if (estimate_converged) {
            result.relative_residual = std::abs(g[k]) / b_norm;
            result.converged = true;
            return result;
        }
    }
    result.relative_residual = (b - apply(result.x, scratch)).norm() / b_norm;
    result.converged = result.relative_residual <= tolerance;
    return result;
}

}  // namespace

KrylovResult gmres(const LinearOperator& A, const LinearOperator& P, const Eigen::VectorXd& b,
                   const Eigen::VectorXd& x0, double tolerance, int restart, int max_iterations) {
    const auto apply = [&A](const Eigen::VectorXd& v, Eigen::MatrixXd&) { return A(v); };
    return restarted_gmres(apply, P, b, x0, tolerance, restart, max_iterations, nullptr);
}

ImagedKrylovResult gmres(const ImagingOperator& A, const Eigen::VectorXd& b, double tolerance,
                         int restart, int max_iterations) {
    ImagedKrylovResult result;
    const LinearOperator identity = [](const Eigen::VectorXd& v) { return v; };
    static_cast<KrylovResult&>(result) =
        restarted_gmres(A, identity, b, Eigen::VectorXd::Zero(b.size()), tolerance, restart,
                        max_iterations, &result.image);
    return result;
}

}  // namespace genflow::detail
