// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "genflow/mesh.h"

namespace genflow {

/// How bad a finding is. Errors make every genflow algorithm refuse the mesh; warnings are
/// conditions the algorithms tolerate (each one's `\note` says how).
enum class Severity { Warning, Error };

/// One finding of `validate()`, with a one-line message such as
/// "12 zero-area faces (first: face 301)".
struct ValidationIssue {
    Severity severity = Severity::Warning;
    std::string message;
};

/// The largest coordinate magnitude a mesh may have. Computed quantities go up to the fourth
/// power of lengths (squared areas), which then stay below 1e200, far from overflow (a double
/// ends at 1.8e308); any physical unit fits (the observable universe is 1e27 m across).
inline constexpr double kLargestCoordinate = 1e50;

/// Thresholds of `validate()`.
struct ValidationOptions {
    /// A face whose smallest angle is below this (in degrees), but whose area is not zero, is
    /// reported as a sliver.
    double sliver_angle_degrees = 1.0;
};

/// What `validate()` found. Counts refer to faces whose indices are in range; topology
/// (edges, manifoldness, components, genus) is computed on faces with three distinct in-range
/// indices.
struct ValidationReport {
    Eigen::Index num_vertices = 0;
    Eigen::Index num_faces = 0;
    Eigen::Index num_edges = 0;  ///< undirected edges

    Eigen::Index non_finite_vertices = 0;  ///< vertices with a NaN or infinite coordinate
    Eigen::Index huge_vertices = 0;  ///< vertices with a coordinate beyond ±kLargestCoordinate
    Eigen::Index out_of_range_faces = 0;              ///< faces with an index outside [0, #V)
    Eigen::Index repeated_index_faces = 0;            ///< faces such as (a, a, b)
    Eigen::Index zero_area_faces = 0;                 ///< area zero up to rounding
    Eigen::Index sliver_faces = 0;                    ///< smallest angle below the threshold
    Eigen::Index duplicate_faces = 0;                 ///< extra copies of a face (same vertex set)
    Eigen::Index non_manifold_edges = 0;              ///< edges shared by more than two faces
    Eigen::Index non_manifold_vertices = 0;           ///< vertices whose faces form several fans
    Eigen::Index boundary_edges = 0;                  ///< edges of exactly one face
    Eigen::Index boundary_loops = 0;                  ///< connected chains of boundary edges
    Eigen::Index inconsistent_orientation_edges = 0;  ///< two faces run the edge the same way
    Eigen::Index unreferenced_vertices = 0;           ///< vertices no face uses
    Eigen::Index components = 0;                      ///< connected components of the faces

    /// V − E + F over referenced vertices.
    Eigen::Index euler_characteristic = 0;
    /// Total genus, Σ over components; set only for manifold, consistently oriented meshes:
    /// g = (2·components − boundary_loops − χ)/2.
    std::optional<Eigen::Index> genus;
    /// Signed enclosed volume < 0 on a closed, consistently oriented mesh: faces point inward.
    bool inward_oriented = false;

    /// Every finding, errors first, in a fixed order.
    std::vector<ValidationIssue> issues;

    /// No finding of Severity::Error.
    [[nodiscard]] bool ok() const;
    /// Edge-manifold and vertex-manifold.
    [[nodiscard]] bool manifold() const {
        return non_manifold_edges == 0 && non_manifold_vertices == 0;
    }
    /// No boundary edges.
    [[nodiscard]] bool closed() const { return boundary_edges == 0; }
    /// The first error's message, or an empty string.
    [[nodiscard]] std::string first_error() const;
};

/// Checks everything about `mesh` that an algorithm might trip over: this is the
/// one expensive check, O(#F log #F), that the CLI and the pipelines run once per input.
///
/// Errors (the mesh is refused): no vertices, no faces, non-finite coordinates, indices out of
/// range. Warnings: every other finding, and faces pointing inward on a closed mesh.
[[nodiscard]] ValidationReport validate(const TriangleMesh& mesh,
                                        const ValidationOptions& options = {});

}  // namespace genflow
