// SPDX-License-Identifier: MIT
#include "numerics/supernodal_solve.h"

#ifdef GENFLOW_HAS_CHOLMOD

#include <cstddef>
#include <vector>

#include "numerics/factor_solves.h"

namespace genflow::detail {

bool fits_supernodal_solve(const cholmod_factor& factor, Eigen::Index columns) {
    return factor.is_super != 0 && readable_ll_factor(factor) && columns >= 1 &&
           columns <= kSupernodalSolveColumns;
}

// X = A⁻¹ B = Pᵀ L⁻ᵀ L⁻¹ P B, with (P B)_k = B_{perm[k]}.
Eigen::MatrixXd supernodal_solve(const cholmod_factor& factor, const Eigen::MatrixXd& B) {
    static_assert(kSupernodalSolveColumns <= kFactorSolveColumns);
    const auto n = static_cast<Eigen::Index>(factor.n);
    const auto columns = static_cast<int>(B.cols());
    const auto* perm = static_cast<const int*>(factor.Perm);
    const auto row_of = [perm](Eigen::Index k) { return perm != nullptr ? perm[k] : k; };
    std::vector<double> z(static_cast<std::size_t>(columns * n));
    for (Eigen::Index k = 0; k < n; ++k) {
        for (int c = 0; c < columns; ++c) {
            z[static_cast<std::size_t>(columns * k + c)] = B(row_of(k), c);
        }
    }
    lower_solve(factor, z.data(), columns);
    upper_solve(factor, z.data(), columns);
    Eigen::MatrixXd X(n, columns);
    for (Eigen::Index k = 0; k < n; ++k) {
        for (int c = 0; c < columns; ++c) {
            X(row_of(k), c) = z[static_cast<std::size_t>(columns * k + c)];
        }
    }
    return X;
}

}  // namespace genflow::detail

#endif
