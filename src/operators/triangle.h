// SPDX-License-Identifier: MIT
// Private per-triangle geometry shared by the operators: edge vectors, area, degeneracy and
// clamped cotangents, computed the same way everywhere.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/mesh.h"
#include "genflow/mesh/validate.h"

namespace genflow::detail {

/// x is finite and x > lo (x >= lo). isfinite is tested first because an ordered comparison
/// with NaN raises FE_INVALID, which our Debug tests trap: checking a NaN parameter must not
/// itself be the floating-point error.
inline bool finite_above(double x, double lo) {
    return std::isfinite(x) && x > lo;
}
inline bool finite_at_least(double x, double lo) {
    return std::isfinite(x) && x >= lo;
}

/// True if no coordinate is NaN or infinite. Written with std::isfinite rather than Eigen's
/// allFinite(), which computes x − x and so raises FE_INVALID on infinities (our Debug tests
/// trap floating-point exceptions).
template <typename Derived>
bool all_finite(const Eigen::PlainObjectBase<Derived>& V) {
    return std::all_of(V.data(), V.data() + V.size(), [](double x) { return std::isfinite(x); });
}

/// True if every coordinate is finite and within ±kLargestCoordinate: positions every operator
/// takes. A flow's step outside them has diverged.
template <typename Derived>
bool within_coordinate_range(const Eigen::PlainObjectBase<Derived>& V) {
    return std::all_of(V.data(), V.data() + V.size(), [](double x) {
        return std::isfinite(x) && std::abs(x) <= kLargestCoordinate;
    });
}

/// Throws InvalidInput naming `function` unless every index of F lies in [0, #V) and every
/// coordinate of V is finite and within ±kLargestCoordinate. O(#V + #F): cheap enough for every
/// public entry point.
inline void require_valid_mesh(const TriangleMesh& mesh, const char* function) {
    if (mesh.F.size() > 0 && (mesh.F.minCoeff() < 0 || mesh.F.maxCoeff() >= mesh.V.rows())) {
        throw InvalidInput(std::string(function) + ": face indices must lie in [0, " +
                           std::to_string(mesh.V.rows()) + "), got [" +
                           std::to_string(mesh.F.minCoeff()) + ", " +
                           std::to_string(mesh.F.maxCoeff()) + "]");
    }
    if (!all_finite(mesh.V)) {
        throw InvalidInput(std::string(function) + ": vertex positions must be finite");
    }
    if (mesh.V.size() > 0 && mesh.V.cwiseAbs().maxCoeff() > kLargestCoordinate) {
        throw InvalidInput(std::string(function) +
                           ": vertex positions must lie within ±1e50 (kLargestCoordinate)");
    }
}

/// Corner positions and derived quantities of face f.
struct Triangle {
    Eigen::Vector3d x[3];
    Eigen::Vector3d cross;  // (x1 − x0)×(x2 − x0): twice the area times the unit normal
    double double_area = 0;

    Triangle(const TriangleMesh& mesh, Eigen::Index f) {
        for (int k = 0; k < 3; ++k) {
            x[k] = mesh.V.row(mesh.F(f, k)).transpose();
        }
        cross = (x[1] - x[0]).cross(x[2] - x[0]);
        double_area = cross.norm();
    }

    /// Zero area up to rounding, relative to the longest edge: no normal, no angles.
    [[nodiscard]] bool degenerate() const {
        const double longest = std::max({(x[1] - x[0]).squaredNorm(), (x[2] - x[1]).squaredNorm(),
                                         (x[0] - x[2]).squaredNorm()});
        return !(double_area > 1e-12 * longest);
    }

    [[nodiscard]] double area() const { return 0.5 * double_area; }

    /// Edge vector opposite corner k, from corner k+1 to corner k+2.
    [[nodiscard]] Eigen::Vector3d opposite_edge(int k) const {
        return x[(k + 2) % 3] - x[(k + 1) % 3];
    }

    /// cot of the angle at corner k (unclamped). Only for non-degenerate faces.
    [[nodiscard]] double cot(int k) const {
        const Eigen::Vector3d u = x[(k + 1) % 3] - x[k];
        const Eigen::Vector3d v = x[(k + 2) % 3] - x[k];
        return u.dot(v) / double_area;
    }

    /// The three cotangents, scaled together so that none exceeds max_cot in magnitude. Scaling
    /// all three by one factor keeps the face's stiffness matrix positive semi-definite
    /// (cot·cot sums stay ≥ 0); clamping each one alone would not, for caps near 180°.
    [[nodiscard]] Eigen::Vector3d bounded_cots(double max_cot) const {
        Eigen::Vector3d c(cot(0), cot(1), cot(2));
        const double largest = c.cwiseAbs().maxCoeff();
        if (largest > max_cot) {
            c *= max_cot / largest;
        }
        return c;
    }
};

}  // namespace genflow::detail
