// SPDX-License-Identifier: MIT
#include "genflow/evaluation/scan_defects.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "genflow/evaluation/single_view.h"
#include "genflow/exceptions.h"
#include "genflow/mesh/edges.h"
#include "genflow/mesh/face_selection.h"
#include "genflow/operators/area.h"
#include "genflow/operators/mesh_size.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

void check_defects(const ScanDefects& defects) {
    const bool counts_valid = defects.holes >= 0 && defects.fragments >= 0;
    const bool lengths_valid = detail::finite_at_least(defects.hole_radius, 0) &&
                               detail::finite_at_least(defects.fragment_radius, 0) &&
                               detail::finite_at_least(defects.noise, 0);
    if (!counts_valid || !lengths_valid) {
        throw InvalidInput(
            "with_scan_defects: counts, radii and noise must be finite and non-negative");
    }
    if (!(detail::finite_at_least(defects.out_of_frame, 0) && defects.out_of_frame < 1)) {
        throw InvalidInput("with_scan_defects: the share out of the frame must lie in [0, 1)");
    }
}

Eigen::RowVector3d centroid(const TriangleMesh& mesh, Eigen::Index face) {
    return (mesh.V.row(mesh.F(face, 0)) + mesh.V.row(mesh.F(face, 1)) +
            mesh.V.row(mesh.F(face, 2))) /
           3;
}

// Points spread uniformly over the surface: the centroids of faces drawn in proportion to
// their area. None on a mesh without area.
class AreaUniformCentres {
public:
    explicit AreaUniformCentres(const TriangleMesh& mesh) : mesh_(mesh) {
        if (mesh.F.rows() > 0) {
            const Eigen::VectorXd areas = face_areas(mesh);
            if (areas.sum() > 0) {
                pick_ = std::discrete_distribution<Eigen::Index>(areas.data(),
                                                                 areas.data() + areas.size());
            }
        }
    }

    [[nodiscard]] bool empty() const { return !pick_; }

    Eigen::RowVector3d operator()(std::mt19937_64& random) {
        return centroid(mesh_, (*pick_)(random));
    }

private:
    const TriangleMesh& mesh_;
    std::optional<std::discrete_distribution<Eigen::Index>> pick_;
};

// The faces whose centroid lies within `radius` of `centre`.
std::vector<Eigen::Index> faces_near(const TriangleMesh& mesh, const Eigen::RowVector3d& centre,
                                     double radius) {
    std::vector<Eigen::Index> near;
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        if ((centroid(mesh, f) - centre).norm() <= radius) {
            near.push_back(f);
        }
    }
    return near;
}

TriangleMesh without_faces(const TriangleMesh& mesh, const std::vector<bool>& dropped) {
    return {mesh.V, faces_where(mesh.F, [&](Eigen::Index f) {
                return !dropped[static_cast<std::size_t>(f)];
            })};
}

TriangleMesh with_holes(const TriangleMesh& mesh, int holes, double radius,
                        std::mt19937_64& random) {
    AreaUniformCentres centre_of_hole(mesh);
    if (holes == 0 || centre_of_hole.empty()) {
        return mesh;
    }
    std::vector<bool> dropped(static_cast<std::size_t>(mesh.F.rows()), false);
    for (int h = 0; h < holes; ++h) {
        for (const Eigen::Index f : faces_near(mesh, centre_of_hole(random), radius)) {
            dropped[static_cast<std::size_t>(f)] = true;
        }
    }
    return without_faces(mesh, dropped);
}

TriangleMesh with_ragged_boundary(const TriangleMesh& mesh, std::mt19937_64& random) {
    const std::vector<bool> on_boundary = boundary_vertices(mesh.F, mesh.V.rows());
    std::bernoulli_distribution coin(0.5);
    std::vector<bool> dropped(static_cast<std::size_t>(mesh.F.rows()), false);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        bool at_boundary = false;
        for (int c = 0; c < 3; ++c) {
            at_boundary = at_boundary || on_boundary[static_cast<std::size_t>(mesh.F(f, c))];
        }
        dropped[static_cast<std::size_t>(f)] = at_boundary && coin(random);
    }
    return without_faces(mesh, dropped);
}

// A fragment lies one to three fragment diameters off where it was copied: near the subject,
// yet apart from it, as stray pieces are.
TriangleMesh with_fragments(const TriangleMesh& mesh, int fragments, double radius,
                            std::mt19937_64& random) {
    AreaUniformCentres centre_of_fragment(mesh);
    if (fragments == 0 || centre_of_fragment.empty()) {
        return mesh;
    }
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> offset(2 * radius, 6 * radius);
    TriangleMesh result = mesh;
    for (int k = 0; k < fragments; ++k) {
        const Eigen::RowVector3d centre = centre_of_fragment(random);
        const Eigen::RowVector3d direction =
            Eigen::RowVector3d(normal(random), normal(random), normal(random)).normalized();
        const Eigen::RowVector3d shift = offset(random) * direction;
        const std::vector<Eigen::Index> faces = faces_near(mesh, centre, radius);
        std::vector<Eigen::Index> copy_of(static_cast<std::size_t>(mesh.V.rows()), -1);
        Eigen::Index vertices = result.V.rows();
        Eigen::Index face_count = result.F.rows();
        result.F.conservativeResize(face_count + static_cast<Eigen::Index>(faces.size()), 3);
        for (const Eigen::Index f : faces) {
            for (int c = 0; c < 3; ++c) {
                Eigen::Index& copy = copy_of[static_cast<std::size_t>(mesh.F(f, c))];
                if (copy < 0) {
                    copy = vertices++;
                    result.V.conservativeResize(vertices, 3);
                    result.V.row(copy) = mesh.V.row(mesh.F(f, c)) + shift;
                }
                result.F(face_count, c) = static_cast<int>(copy);
            }
            ++face_count;
        }
    }
    return result;
}

// The faces with a vertex beyond `share` of the extent along `direction` dropped: the frame's
// edge is a plane, and a face it crosses is not seen whole.
TriangleMesh out_of_frame(const TriangleMesh& mesh, double share,
                          const Eigen::Vector3d& direction) {
    const Eigen::VectorXd height = mesh.V * direction;
    const double edge = height.maxCoeff() - share * (height.maxCoeff() - height.minCoeff());
    return {mesh.V, faces_where(mesh.F, [&](Eigen::Index f) {
                return std::max({height[mesh.F(f, 0)], height[mesh.F(f, 1)],
                                 height[mesh.F(f, 2)]}) <= edge;
            })};
}

void add_noise(TriangleMesh& mesh, double sigma, std::mt19937_64& random) {
    std::normal_distribution<double> normal(0, sigma);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            mesh.V(i, c) += normal(random);
        }
    }
}

}  // namespace

TriangleMesh with_scan_defects(const TriangleMesh& mesh, const ScanDefects& defects,
                               std::uint64_t seed) {
    detail::require_valid_mesh(mesh, "with_scan_defects");
    check_defects(defects);
    const double diagonal = bounding_box_diagonal(mesh);
    const double edge = mesh.F.rows() > 0 ? mean_edge_length(mesh) : 0;
    TriangleMesh result = mesh;
    if (defects.out_of_frame > 0) {
        // Its own draw (the seed's bits flipped by an odd constant, the golden ratio's), so that
        // the other defects are the same with or without it.
        result = out_of_frame(result, defects.out_of_frame,
                              view_direction(seed ^ 0x9e3779b97f4a7c15ULL));
    }
    std::mt19937_64 random(seed);
    result = with_holes(result, defects.holes, defects.hole_radius * diagonal, random);
    if (defects.ragged_boundary) {
        result = with_ragged_boundary(result, random);
    }
    result = with_fragments(result, defects.fragments, defects.fragment_radius * diagonal, random);
    if (defects.noise > 0) {
        add_noise(result, defects.noise * edge, random);
    }
    return result;
}

}  // namespace genflow
