// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>

#include "genflow/mesh.h"

namespace genflow {

/// Accuracy of `surface_distances()`.
struct SurfaceDistanceOptions {
    /// Absolute error allowed on the Hausdorff distances; 0 means 1e-4 × the larger bounding-box
    /// diagonal of the two meshes.
    double hausdorff_tolerance = 0;
    /// Faces are split for the mean and RMS quadrature until their pieces are at most this long;
    /// 0 means half the smaller mean edge length of the two meshes.
    double quadrature_length = 0;
    /// false: the Hausdorff distances alone (what CGAL's bounded_error_Hausdorff_distance
    /// gives), skipping the quadrature of the mean and RMS, which then stay 0.
    bool mean_and_rms = true;
};

/// Distances from the surface of one mesh to the surface of another (not just vertices).
struct OneSidedDistance {
    /// max_{p ∈ from} d(p, to), exact to within `hausdorff_upper_bound − hausdorff`.
    double hausdorff = 0;
    /// A proven upper bound of the true one-sided Hausdorff distance.
    double hausdorff_upper_bound = 0;
    Eigen::Vector3d farthest_point = Eigen::Vector3d::Zero();  ///< where `hausdorff` is attained
    /// Area-weighted mean and RMS of d(p, to) over `from`, by centroid quadrature on split faces.
    double mean = 0;
    double rms = 0;
    /// Proven bounds: |true mean − mean| ≤ mean_error_bound, |true RMS − rms| ≤ rms_error_bound.
    double mean_error_bound = 0;
    double rms_error_bound = 0;
    double area = 0;  ///< area of `from`
};

/// Both directions and their symmetric combinations.
struct SurfaceDistances {
    OneSidedDistance a_to_b;
    OneSidedDistance b_to_a;
    double hausdorff = 0;              ///< max of the two one-sided distances
    double hausdorff_upper_bound = 0;  ///< max of their upper bounds
    double mean = 0;                   ///< (∫_A d(·, B) + ∫_B d(·, A)) / (area A + area B)
    double rms = 0;                    ///< likewise for d²
};

/// Exact surface-to-surface distances in the manner of Metro and CGAL's
/// `bounded_error_Hausdorff_distance`: the distance from a point to the other surface comes from
/// a TriangleBvh; the one-sided Hausdorff distance is found by refining faces whose proven upper
/// bound (the distance is 1-Lipschitz, so on a triangle it is at most min_k(d(c_k) + the
/// longest edge at c_k)) exceeds the best value found by more than the tolerance. The mean and
/// RMS distances use the centroid rule on faces split to `quadrature_length`, whose error is
/// bounded by the same Lipschitz argument. Uses both cores when OpenMP is available.
///
/// \throws InvalidInput if a mesh has no face, bad indices or non-finite coordinates, or an
///         option is negative or not finite.
[[nodiscard]] SurfaceDistances surface_distances(const TriangleMesh& A, const TriangleMesh& B,
                                                 const SurfaceDistanceOptions& options = {});

}  // namespace genflow
