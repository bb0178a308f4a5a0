// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

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

/// Ellipsoid with semi-axes `radii` along x, y, z: an icosphere of `level` (see
/// make_icosphere()), first turned by a random rotation drawn from `sampling_seed` (0: none),
/// so that two seeds sample the same surface at different points, then stretched.
/// \throws InvalidInput as make_icosphere(), or if a radius is not positive and finite.
[[nodiscard]] TriangleMesh make_ellipsoid(int level, const Eigen::Vector3d& radii,
                                          std::uint64_t sampling_seed = 0);

/// An elongated, asymmetric test shape about 6 long: an ellipsoid (3, 0.55, 0.45) with a hump on
/// top of its +x end, thicker towards +x, sagging towards −y at both ends, so that no rotation
/// maps it onto itself, even bent (a symmetric shape makes any alignment ambiguous). Sampled as
/// make_ellipsoid(level, ..., sampling_seed).
[[nodiscard]] TriangleMesh make_limb(int level, std::uint64_t sampling_seed = 0);

/// A joint for bend_at_joints(): the points on the positive side of the plane through `centre`
/// with normal `direction` turn by `angle` (radians) about the line through `centre` along
/// `axis`; the turn is blended in smoothly (smoothstep) over `width` on either side of the plane.
struct Joint {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    double angle = 0;
    double width = 0.1;
};

/// `points` posed by the joints, applied one after the other in the rest frame (so joints
/// should move disjoint parts, e.g. the two ends of a limb): the generated articulated pairs of
/// `genflow demo` and the matching tests, with the rest points as ground truth.
/// \throws InvalidInput if a joint has a zero direction or axis, or a width that is not
///         positive, or a value that is not finite.
[[nodiscard]] Eigen::MatrixX3d bend_at_joints(const Eigen::MatrixX3d& points,
                                              const std::vector<Joint>& joints);

/// Returns `mesh` with every vertex moved by an independent Gaussian offset of standard
/// deviation `sigma` per coordinate, reproducibly from `seed`.
[[nodiscard]] TriangleMesh add_noise(TriangleMesh mesh, double sigma, std::uint64_t seed);

}  // namespace genflow
