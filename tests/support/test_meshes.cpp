// SPDX-License-Identifier: MIT
#include "support/test_meshes.h"

#include <unistd.h>

#include <Eigen/Geometry>
#include <array>
#include <cfenv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <random>
#include <vector>

#include "genflow/mesh/primitives.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/mesh_size.h"
#include "spatial/point_index.h"

namespace genflow::test {

TriangleMesh noisy_icosphere(int level, double relative_sigma, unsigned seed) {
    TriangleMesh mesh = make_icosphere(level);
    return add_noise(mesh, relative_sigma * mean_edge_length(mesh), seed);
}

TriangleMesh noisy_torus(int rings, int sides, double relative_sigma, unsigned seed) {
    TriangleMesh mesh = make_torus(rings, sides);
    return add_noise(mesh, relative_sigma * mean_edge_length(mesh), seed);
}

namespace {

struct Spike {
    Eigen::Vector3d direction;
    double height;
};

std::array<Spike, 5> figure_spikes() {
    return {{{Eigen::Vector3d(0, 0.3, 1).normalized(), 1.0},
             {Eigen::Vector3d(1, -0.2, 0.3).normalized(), 1.4},
             {Eigen::Vector3d(-1, -0.2, 0.3).normalized(), 1.4},
             {Eigen::Vector3d(0.7, 0.3, -1).normalized(), 1.8},
             {Eigen::Vector3d(-0.7, 0.3, -1).normalized(), 1.8}}};
}

Eigen::MatrixX3d posed_figure(const Eigen::MatrixX3d& points) {
    std::vector<Joint> joints;
    double angle = 60;
    for (const Spike& spike : figure_spikes()) {
        joints.push_back({.centre = 1.6 * spike.direction,
                          .direction = spike.direction,
                          .axis = spike.direction.cross(Eigen::Vector3d(0.3, 1, 0.2)).normalized(),
                          .angle = angle * std::numbers::pi / 180,
                          .width = 0.3});
        angle += 10;
    }
    return bend_at_joints(points, joints);
}

}  // namespace

TriangleMesh spiked_figure(int level, std::uint64_t sampling_seed) {
    TriangleMesh mesh = make_ellipsoid(level, Eigen::Vector3d::Ones(), sampling_seed);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        const Eigen::Vector3d u = mesh.V.row(i).normalized();
        double radius = 1;
        for (const Spike& spike : figure_spikes()) {
            radius += spike.height * std::exp((u.dot(spike.direction) - 1) / 0.05);
        }
        mesh.V.row(i) = radius * u;
    }
    return mesh;
}

std::vector<Eigen::Index> figure_mirror(const TriangleMesh& figure) {
    Eigen::MatrixX3d mirrored = figure.V;
    mirrored.col(0) *= -1;
    const detail::PointIndex index(figure.V);
    std::vector<Eigen::Index> mirror;
    for (Eigen::Index v = 0; v < figure.V.rows(); ++v) {
        mirror.push_back(index.nearest(mirrored.row(v).transpose()).first);
    }
    return mirror;
}

PosedSpikedFigure::PosedSpikedFigure()
    : motion{.rotation =
                 Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix(),
             .translation = Eigen::Vector3d(4, -1, 2),
             .scale = 2.5},
      template_mesh(spiked_figure(3, 0)),
      target(spiked_figure(4, 7)) {
    target.V = motion.apply(posed_figure(target.V));
    truth = motion.apply(posed_figure(template_mesh.V));
}

double PosedSpikedFigure::mean_distance(const Eigen::MatrixX3d& placement) const {
    return (placement - truth).rowwise().norm().mean() / bounding_box_diagonal(target);
}

PartModel two_part_arm(const TriangleMesh& mesh) {
    PartModel model;
    model.parts = {{"upper", -1, Eigen::Vector3d::Zero()},
                   {"lower", 0, Eigen::Vector3d(1.0, 0, 0)}};
    Eigen::VectorXi labels(mesh.V.rows());
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        labels[i] = mesh.V(i, 0) > 1.0 ? 1 : 0;
    }
    model.weights = weights_from_labels(labels, 2);
    return model;
}

Eigen::SparseMatrix<double> sphere_h1_matrix(int level, int copies) {
    const TriangleMesh sphere = make_icosphere(level);
    const Eigen::SparseMatrix<double> block =
        mass_matrix(sphere, MassType::Full) + cotan_stiffness(sphere);
    const Eigen::Index n = block.rows();
    std::vector<Eigen::Triplet<double>> entries;
    for (int c = 0; c < copies; ++c) {
        for (Eigen::Index k = 0; k < block.outerSize(); ++k) {
            for (Eigen::SparseMatrix<double>::InnerIterator it(block, k); it; ++it) {
                entries.emplace_back(c * n + it.row(), c * n + it.col(), it.value());
            }
        }
    }
    Eigen::SparseMatrix<double> A(copies * n, copies * n);
    A.setFromTriplets(entries.begin(), entries.end());
    return A;
}

Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, unsigned seed) {
    std::mt19937 generator(seed);
    std::uniform_real_distribution<double> entry(-1, 1);
    Eigen::MatrixXd matrix(rows, cols);
    for (Eigen::Index j = 0; j < cols; ++j) {
        for (Eigen::Index i = 0; i < rows; ++i) {
            matrix(i, j) = entry(generator);
        }
    }
    return matrix;
}

TriangleMesh jittered_grid(int cells, unsigned seed) {
    TriangleMesh mesh = make_grid(cells);
    std::mt19937 generator(seed);
    std::uniform_real_distribution<double> jitter(-0.25 / cells, 0.25 / cells);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        const double x = mesh.V(i, 0);
        const double y = mesh.V(i, 1);
        if (x > 0 && x < 1 && y > 0 && y < 1) {
            mesh.V(i, 0) += jitter(generator);
            mesh.V(i, 1) += jitter(generator);
        }
    }
    return mesh;
}

VertexField finite_difference_gradient(const std::function<double(const TriangleMesh&)>& energy,
                                       const TriangleMesh& mesh, double h) {
    VertexField gradient(mesh.V.rows(), 3);
    TriangleMesh probe = mesh;
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const double x = mesh.V(i, c);
            probe.V(i, c) = x + h;
            const double plus = energy(probe);
            probe.V(i, c) = x - h;
            const double minus = energy(probe);
            probe.V(i, c) = x;
            gradient(i, c) = (plus - minus) / (2 * h);
        }
    }
    return gradient;
}

double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    return (a - b).norm() / b.norm();
}

std::optional<std::filesystem::path> data_directory() {
    const char* from_environment = std::getenv("GENFLOW_DATA");
    const std::filesystem::path directory =
        from_environment != nullptr ? from_environment : GENFLOW_DEFAULT_DATA_DIR;
    if (std::filesystem::is_directory(directory)) {
        return directory;
    }
    return std::nullopt;
}

TemporaryDirectory::TemporaryDirectory() {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("genflow-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
}

TemporaryDirectory::~TemporaryDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

FloatingPointTrapsOff::FloatingPointTrapsOff() {
#ifdef __GLIBC__
    saved_ = fegetexcept();
    fedisableexcept(FE_ALL_EXCEPT);
#endif
}

FloatingPointTrapsOff::~FloatingPointTrapsOff() {
#ifdef __GLIBC__
    std::feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(saved_);
#endif
}

void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream file(path, std::ios::binary);
    file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace genflow::test
