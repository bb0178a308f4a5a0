// SPDX-License-Identifier: MIT
// Mean curvature from the discrete operators: ΔX = −M⁻¹KX = −2Hn (docs/formulas.md §1).
// Usage: mean_curvature_example [MESH]   (default: a generated sphere of radius 2, H = 0.5)
#include <iostream>

#include "genflow/io/read_mesh.h"
#include "genflow/mesh/primitives.h"
#include "genflow/mesh/validate.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/normals.h"

int main(int argc, char** argv) {
    try {
        const genflow::TriangleMesh mesh =
            argc > 1 ? genflow::read_mesh(argv[1]) : genflow::make_icosphere(4, 2.0);
        const genflow::ValidationReport report = genflow::validate(mesh);
        if (!report.ok()) {
            std::cerr << "mesh refused: " << report.first_error() << '\n';
            return 2;
        }
        const genflow::VertexField KX = genflow::cotan_stiffness(mesh) * mesh.V;
        const Eigen::VectorXd m = genflow::lumped_masses(mesh, genflow::MassType::Voronoi);
        const Eigen::MatrixX3d N = genflow::vertex_normals(mesh);
        Eigen::VectorXd H(mesh.V.rows());
        for (Eigen::Index i = 0; i < H.size(); ++i) {
            H[i] = m[i] > 0 ? KX.row(i).dot(N.row(i)) / (2 * m[i]) : 0.0;
        }
        std::cout << "mean curvature: min " << H.minCoeff() << ", mean " << H.mean() << ", max "
                  << H.maxCoeff() << '\n';
    } catch (const std::exception& e) {
        std::cerr << e.what() << '\n';
        return 1;
    }
    return 0;
}
