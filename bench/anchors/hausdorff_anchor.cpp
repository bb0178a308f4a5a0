// SPDX-License-Identifier: MIT
// The anchor of `genflow distance`: CGAL's symmetric Hausdorff distance with a bounded error
// (Polygon_mesh_processing::bounded_error_symmetric_Hausdorff_distance, CGAL 5.5 from Debian's
// libcgal-dev), the error bound a share of the first mesh's bounding-box diagonal.
//
// Usage: hausdorff_anchor A B SHARE   (SHARE: the error bound over A's diagonal, e.g. 1e-4)
// Prints the distance.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: hausdorff_anchor A B SHARE\n");
        return 2;
    }
    Mesh a;
    Mesh b;
    if (!CGAL::IO::read_polygon_mesh(argv[1], a) || !CGAL::IO::read_polygon_mesh(argv[2], b)) {
        std::fprintf(stderr, "hausdorff_anchor: cannot read the meshes\n");
        return 2;
    }
    const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(a);
    const double diagonal =
        std::sqrt(std::pow(box.xmax() - box.xmin(), 2) + std::pow(box.ymax() - box.ymin(), 2) +
                  std::pow(box.zmax() - box.zmin(), 2));
    const double distance =
        CGAL::Polygon_mesh_processing::bounded_error_symmetric_Hausdorff_distance<
            CGAL::Sequential_tag>(a, b, std::atof(argv[3]) * diagonal);
    std::printf("hausdorff_anchor: %.10g\n", distance);
    return 0;
}
