// SPDX-License-Identifier: MIT
#include "support/test_meshes.h"

#include <unistd.h>

#include <cfenv>
#include <cstdlib>
#include <fstream>
#include <random>

#include "genflow/mesh/primitives.h"
#include "genflow/operators/mesh_size.h"

namespace genflow::test {

TriangleMesh noisy_icosphere(int level, double relative_sigma, unsigned seed) {
    TriangleMesh mesh = make_icosphere(level);
    return add_noise(mesh, relative_sigma * mean_edge_length(mesh), seed);
}

TriangleMesh noisy_torus(int rings, int sides, double relative_sigma, unsigned seed) {
    TriangleMesh mesh = make_torus(rings, sides);
    return add_noise(mesh, relative_sigma * mean_edge_length(mesh), seed);
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
