// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>

#include "genflow/mesh.h"

namespace genflow {

/// Icosphere: an icosahedron subdivided `level` times (each triangle into four) with every
/// vertex pushed onto the sphere of `radius` about the origin. Closed, genus 0, outward faces;
/// 10·4^level + 2 vertices and 20·4^level faces.
/// \throws InvalidInput if level is not in [0, 9] or radius is not positive and finite.
[[nodiscard]] TriangleMesh make_icosphere(int level, double radius = 1.0);

/// Torus about the z axis: `rings` vertices around the axis, `sides` around the tube,
/// tube centre at distance `major_radius`, tube radius `minor_radius`. Closed, genus 1, outward
/// faces; rings·sides vertices and 2·rings·sides faces.
/// \throws InvalidInput unless rings, sides >= 3 and 0 < minor_radius < major_radius.
[[nodiscard]] TriangleMesh make_torus(int rings, int sides, double major_radius = 1.0,
                                      double minor_radius = 0.4);

/// Flat open square [0, size]² in the z = 0 plane, split into cells×cells squares and each
/// square into two triangles, faces towards +z. One boundary loop; (cells+1)² vertices.
/// \throws InvalidInput unless cells >= 1 and size > 0.
[[nodiscard]] TriangleMesh make_grid(int cells, double size = 1.0);

/// Returns `mesh` with every vertex moved by an independent Gaussian offset of standard
/// deviation `sigma` per coordinate, reproducibly from `seed`.
[[nodiscard]] TriangleMesh add_noise(TriangleMesh mesh, double sigma, std::uint64_t seed);

}  // namespace genflow
