// SPDX-License-Identifier: MIT
// The anchors' inputs made from the shared meshes (bench/anchors/anchors.py): a mesh coarsened
// to a share of its vertices (coarsen_to_share(), the 10 % decimations the Hausdorff rows
// compare with), or subdivided once, each face into four at its edges' midpoints (the 173K
// armadillo of the fairing rows: the same surface, four times the vertices).
//
// Usage: decimate IN OUT (--ratio R | --subdivide)
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "genflow/io/read_mesh.h"
#include "genflow/io/write_mesh.h"
#include "genflow/matching/multiresolution.h"

namespace {

// Each face into four, a new vertex at the midpoint of each edge (shared by its two faces).
genflow::TriangleMesh subdivided(const genflow::TriangleMesh& mesh) {
    std::vector<Eigen::RowVector3d> vertices(static_cast<std::size_t>(mesh.V.rows()));
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
        vertices[static_cast<std::size_t>(v)] = mesh.V.row(v);
    }
    std::map<std::pair<int, int>, int> midpoint;
    const auto middle = [&](int a, int b) {
        const auto key = std::minmax(a, b);
        const auto [found, added] = midpoint.try_emplace(key, static_cast<int>(vertices.size()));
        if (added) {
            vertices.push_back(0.5 * (mesh.V.row(a) + mesh.V.row(b)));
        }
        return found->second;
    };
    Eigen::MatrixX3i faces(4 * mesh.F.rows(), 3);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const int a = mesh.F(f, 0);
        const int b = mesh.F(f, 1);
        const int c = mesh.F(f, 2);
        const int ab = middle(a, b);
        const int bc = middle(b, c);
        const int ca = middle(c, a);
        faces.row(4 * f) << a, ab, ca;
        faces.row(4 * f + 1) << ab, b, bc;
        faces.row(4 * f + 2) << ca, bc, c;
        faces.row(4 * f + 3) << ab, bc, ca;
    }
    genflow::TriangleMesh result{Eigen::MatrixX3d(static_cast<Eigen::Index>(vertices.size()), 3),
                                 faces};
    for (std::size_t v = 0; v < vertices.size(); ++v) {
        result.V.row(static_cast<Eigen::Index>(v)) = vertices[v];
    }
    return result;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: decimate IN OUT (--ratio R | --subdivide)\n");
        return 2;
    }
    try {
        const genflow::TriangleMesh mesh = genflow::read_mesh(argv[1]);
        const std::string how = argv[3];
        if (how == "--subdivide") {
            genflow::write_mesh(argv[2], subdivided(mesh));
        } else if (how == "--ratio" && argc > 4) {
            genflow::write_mesh(argv[2], genflow::coarsen_to_share(mesh, std::atof(argv[4])).mesh);
        } else {
            std::fprintf(stderr, "decimate: expected --ratio R or --subdivide\n");
            return 2;
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "decimate: %s\n", error.what());
        return 2;
    }
    return 0;
}
