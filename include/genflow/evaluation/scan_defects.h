// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>

#include "genflow/mesh.h"

namespace genflow {

/// The defects of a real scan, made on a mesh for benchmarks (with_scan_defects()). Lengths are
/// fractions of the mesh's bounding-box diagonal or of its mean edge, so the same defects are
/// made at any scale.
struct ScanDefects {
    /// A part out of the frame: the share of the mesh's extent along a random direction beyond
    /// which its faces are cut off, as where a subject reaches past a scanner's field of view
    /// (0.15 of a standing body's height takes the feet and ankles). 0: none.
    double out_of_frame = 0;
    /// Holes: discs of faces removed around area-uniform random points, as where a scanner saw
    /// nothing (occlusion, dark or shiny patches).
    int holes = 0;
    /// Radius of each hole, in diagonals: 0.03 is about a palm on a body.
    double hole_radius = 0.03;
    /// Loose fragments: discs of the surface copied and moved off it, as the stray pieces of
    /// background and hair a scan keeps.
    int fragments = 0;
    /// Radius of each fragment, in diagonals.
    double fragment_radius = 0.02;
    /// A ragged boundary: each face at the boundary dropped with probability 1/2, leaving a
    /// jagged edge and loose single faces, as a scanner's grazing rays do.
    bool ragged_boundary = false;
    /// Gaussian noise on every vertex coordinate, σ in mean edge lengths.
    double noise = 0;
};

/// `mesh` with `defects`, drawn from `seed` (the same mesh for the same seed). The frame's cut,
/// holes and the ragged boundary drop faces; the vertices are all kept, in order (those of no kept
/// face unreferenced), so a vertex index of the result is one of `mesh`; the fragments' vertices
/// follow them.
/// \throws InvalidInput if the mesh is invalid, a field of `defects` is negative or not finite,
///         or `out_of_frame` is 1 or more.
[[nodiscard]] TriangleMesh with_scan_defects(const TriangleMesh& mesh, const ScanDefects& defects,
                                             std::uint64_t seed);

}  // namespace genflow
