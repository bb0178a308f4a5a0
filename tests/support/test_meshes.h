// SPDX-License-Identifier: MIT
// Meshes and helpers shared by the tests. Everything is generated: no data files needed.
#pragma once

#include <Eigen/SparseCore>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "genflow/matching/rigid_alignment.h"
#include "genflow/mesh.h"
#include "genflow/parts/part_model.h"

namespace genflow::test {

/// Icosphere of `level` with every vertex moved by Gaussian noise of `relative_sigma` times the
/// mean edge length: irregular, but still closed and well-shaped.
TriangleMesh noisy_icosphere(int level, double relative_sigma = 0.1, unsigned seed = 1);

/// Torus with vertex noise, as above.
TriangleMesh noisy_torus(int rings, int sides, double relative_sigma = 0.1, unsigned seed = 2);

/// A matrix of entries uniform in [-1, 1] drawn from its own seeded generator: the same in
/// every test order, unlike Eigen's Random(), which draws from the process's std::rand().
Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, unsigned seed);

/// M + K (full mass matrix, cotangent stiffness) of an icosphere of `level`, `copies` of it
/// along the diagonal: a symmetric positive definite matrix of a surface mesh's pattern.
Eigen::SparseMatrix<double> sphere_h1_matrix(int level, int copies = 1);

/// A figure: a unit sphere with a head, two arms and two legs, spikes of different lengths but
/// for the pairs, mirror images of one another across the plane x = 0, so that a reflection is
/// its only symmetry (a map that follows it turns the surface over). Sampled as
/// make_ellipsoid(level, 1, sampling_seed): two seeds sample the same surface differently.
TriangleMesh spiked_figure(int level, std::uint64_t sampling_seed);

/// Each vertex of a spiked figure at rest (symmetric across x = 0) with the vertex nearest to
/// its mirror image: the figure's one isometry, which reverses its orientation.
std::vector<Eigen::Index> figure_mirror(const TriangleMesh& figure);

/// A pair of spiked figures: the template at rest (level 3), and the target, another sampling
/// (level 4, 4× the vertices) with every spike bent by 60–100° (each its own angle, about its
/// own axis, at 1.6 from the centre, beyond the reach of the other spikes' bends), turned,
/// scaled by `motion` and moved; `truth` is where each template vertex belongs on it.
struct PosedSpikedFigure {
    Similarity motion;
    TriangleMesh template_mesh;
    TriangleMesh target;
    Eigen::MatrixX3d truth;

    PosedSpikedFigure();
    /// Mean distance of `placement` (one row per template vertex) to `truth`, over the
    /// target's bounding-box diagonal.
    [[nodiscard]] double mean_distance(const Eigen::MatrixX3d& placement) const;
};

/// The generated limb (make_limb()) as two parts: the upper arm (x ≤ 1) the root, the forearm
/// its child, jointed at (1, 0, 0).
PartModel two_part_arm(const TriangleMesh& mesh);

/// A planar grid whose interior vertices are jittered inside the plane z = 0.
TriangleMesh jittered_grid(int cells, unsigned seed = 3);

/// Central finite differences of a scalar function of the positions, step h.
VertexField finite_difference_gradient(const std::function<double(const TriangleMesh&)>& energy,
                                       const TriangleMesh& mesh, double h = 1e-6);

/// ‖a − b‖ / ‖b‖ (Frobenius).
double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

/// The data directory: $GENFLOW_DATA, else ../shared/data beside the source tree; nothing if
/// it does not exist (tests that need it skip with a message).
std::optional<std::filesystem::path> data_directory();

/// A fresh, empty temporary directory, removed when the object dies.
class TemporaryDirectory {
public:
    TemporaryDirectory();
    ~TemporaryDirectory();
    TemporaryDirectory(const TemporaryDirectory&) = delete;
    TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
    [[nodiscard]] const std::filesystem::path& path() const { return path_; }
    [[nodiscard]] std::filesystem::path operator/(const std::string& name) const {
        return path_ / name;
    }

private:
    std::filesystem::path path_;
};

/// Turns off the floating-point traps of Debug test runs (tests/support/test_main.cpp) for a
/// scope, for tests that overflow on purpose; restores them, with cleared flags, afterwards.
class FloatingPointTrapsOff {
public:
    FloatingPointTrapsOff();
    ~FloatingPointTrapsOff();
    FloatingPointTrapsOff(const FloatingPointTrapsOff&) = delete;
    FloatingPointTrapsOff& operator=(const FloatingPointTrapsOff&) = delete;

private:
    int saved_ = 0;
};

/// Writes `bytes` to `path` as they are (for malformed-file tests).
void write_bytes(const std::filesystem::path& path, const std::string& bytes);

}  // namespace genflow::test
