// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "genflow/mesh.h"

namespace genflow {

/// What repair_surface() changed, by kind.
struct RepairCounts {
    Eigen::Index repeated_index_faces = 0;  ///< faces such as (a, a, b), removed
    Eigen::Index vertices_welded = 0;       ///< vertices merged into an earlier identical one
    Eigen::Index duplicate_faces = 0;  ///< extra copies of a face (either orientation), removed
    Eigen::Index vertices_split = 0;   ///< copies made of non-manifold vertices, one per extra fan
    Eigen::Index components_left_out = 0;    ///< components other than the largest
    double area_left_out = 0;                ///< their share of the surface area, in [0, 1)
    Eigen::Index unreferenced_vertices = 0;  ///< input vertices that no kept face uses
};

/// A mesh made into one connected, manifold surface, and how its vertices relate to the input's.
struct RepairedSurface {
    TriangleMesh mesh;
    /// Per vertex of `mesh`, the input vertex it stands for (a split vertex's copies all name it).
    std::vector<Eigen::Index> source_vertex;
    /// Per input vertex, the vertex of `mesh` that carries it (for a split vertex, the copy of
    /// its largest fan), or −1 if none does: unreferenced, or in a component left out.
    std::vector<Eigen::Index> repaired_vertex;
    RepairCounts counts;

    /// False if `mesh` is the input itself (same vertices in the same order, same faces).
    [[nodiscard]] bool changed() const;
    /// One line of what was done, e.g. "removed 2 duplicate faces, split 3 non-manifold
    /// vertices"; empty if nothing was.
    [[nodiscard]] std::string summary() const;
};

/// Parameters of repair_surface().
struct RepairOptions {
    /// Keep only the connected component of largest area (step 5). Off, every component is
    /// kept: the pieces of a partial scan are all surface that a match must cover.
    bool largest_component_only = true;
};

/// The input as one manifold surface, for the algorithms that deform a surface or analyse its
/// intrinsic geometry (matching). In order:
/// 1. faces with a repeated vertex are removed (they have no area and no orientation);
/// 2. vertices at identical coordinates are welded into the first (an exporter writes a
///    point twice, at a seam of its texture or normals, with the same digits; a tolerance
///    would need a scale and could join the two sides of a thin part);
/// 3. extra copies of a face (the same three vertices in either orientation) are removed;
/// 4. faces that share an edge with more than one other face are no longer joined across it,
///    and every vertex whose faces then form several fans is split into one vertex per fan
///    (the largest fan keeps it), so that every edge has at most two faces and every vertex
///    one fan;
/// 5. of the connected components, the one with the largest area is kept (unless
///    RepairOptions::largest_component_only is off).
/// Orientation is left as it is. A manifold, connected input comes back unchanged.
/// \throws InvalidInput if the mesh is invalid (validate()) or no face is left.
[[nodiscard]] RepairedSurface repair_surface(const TriangleMesh& mesh,
                                             const RepairOptions& options = {});

}  // namespace genflow
