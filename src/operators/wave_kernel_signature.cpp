// SPDX-License-Identifier: MIT
#include "genflow/operators/wave_kernel_signature.h"

#include <cmath>

#include "genflow/exceptions.h"

namespace genflow {

namespace {

// Eigenvalues below this share of the largest count as zero: the constant functions of the
// components, whose λ are zero up to the solver's rounding.
constexpr double kZeroEigenvalue = 1e-10;
// The bands' width over their spacing (Aubry et al.'s choice).
constexpr double kBandWidth = 7;

}  // namespace

Eigen::MatrixXd wave_kernel_signature(const LaplacianEigenbasis& basis, Eigen::Index energies) {
    const double area = basis.masses.sum();
    if (energies < 1 || !(area > 0)) {
        throw InvalidInput("wave_kernel_signature: need energies >= 1 and a basis with area");
    }
    const double largest = basis.values.size() > 0 ? basis.values.maxCoeff() : 0;
    Eigen::Index first = 0;
    while (first < basis.values.size() && !(basis.values(first) > kZeroEigenvalue * largest)) {
        ++first;
    }
    const Eigen::Index count = basis.values.size() - first;
    if (count < 3) {
        throw InvalidInput(
            "wave_kernel_signature: the basis has fewer than 3 non-zero eigenvalues");
    }
    const Eigen::ArrayXd log_values = basis.values.tail(count).array().log();
    const double low = log_values(0);
    const double high = log_values(count - 1);
    const double sigma = kBandWidth * (high - low) / static_cast<double>(energies);
    const Eigen::MatrixXd squared = basis.functions.rightCols(count).array().square().matrix();
    Eigen::MatrixXd signature(basis.functions.rows(), energies);
    for (Eigen::Index s = 0; s < energies; ++s) {
        const double t =
            energies > 1 ? static_cast<double>(s) / static_cast<double>(energies - 1) : 0.5;
        const double e = (low + 2 * sigma) + t * ((high - 2 * sigma) - (low + 2 * sigma));
        const Eigen::VectorXd band =
            (-(log_values - e).square() / (2 * sigma * sigma)).exp().matrix();
        signature.col(s) = squared * band * (area / band.sum());
    }
    return signature;
}

}  // namespace genflow
