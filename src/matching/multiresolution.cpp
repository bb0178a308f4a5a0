// SPDX-License-Identifier: MIT
#include "genflow/matching/multiresolution.h"

#include <meshoptimizer.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/mesh/edges.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/normals.h"
#include "genflow/spatial/closest_point.h"
#include "numerics/nearest_orthogonal.h"
#include "operators/triangle.h"
#include "spatial/point_index.h"
#include "spatial/surface_paths.h"

namespace genflow {

CoarseMesh coarsen_to_share(const TriangleMesh& mesh, double share) {
    if (!detail::finite_above(share, 0) || share > 1) {  // isfinite first: NaN raises no trap
        throw InvalidInput("coarsen_to_share: the share must be in (0, 1]");
    }
    const auto vertices =
        static_cast<Eigen::Index>(std::ceil(share * static_cast<double>(mesh.V.rows())));
    return coarsen(mesh, std::max<Eigen::Index>(vertices, 4));
}

CoarseMesh coarsen(const TriangleMesh& mesh, Eigen::Index target_vertices) {
    detail::require_valid_mesh(mesh, "coarsen");
    if (mesh.F.rows() == 0) {
        throw InvalidInput("coarsen: the mesh has no faces");
    }
    if (target_vertices < 4) {
        throw InvalidInput("coarsen: target_vertices must be at least 4");
    }
    const Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> positions = mesh.V.cast<float>();
    const Eigen::Matrix<unsigned, Eigen::Dynamic, 3, Eigen::RowMajor> faces =
        mesh.F.cast<unsigned>();
    // A closed triangle mesh has about twice as many faces as vertices.
    const double ratio = static_cast<double>(target_vertices) / static_cast<double>(mesh.V.rows());
    const auto target_indices = static_cast<std::size_t>(
        3 * std::clamp<double>(std::round(ratio * static_cast<double>(mesh.F.rows())), 4,
                               static_cast<double>(mesh.F.rows())));
    std::vector<unsigned> simplified(static_cast<std::size_t>(faces.size()));
    const std::size_t count = meshopt_simplify(
        simplified.data(), faces.data(), static_cast<std::size_t>(faces.size()), positions.data(),
        static_cast<std::size_t>(mesh.V.rows()), 3 * sizeof(float), target_indices,
        /*target_error=*/1.0F, meshopt_SimplifyLockBorder, nullptr);

    // meshoptimizer can leave a few fins: two faces on the same three vertices (1–13 on the
    // 28K-vertex TOSCA cat). Both copies go; the surface around them stays manifold.
    std::vector<std::array<unsigned, 3>> sorted(count / 3);
    for (std::size_t f = 0; f < count / 3; ++f) {
        sorted[f] = {simplified[3 * f], simplified[3 * f + 1], simplified[3 * f + 2]};
        std::sort(sorted[f].begin(), sorted[f].end());
    }
    std::vector<std::size_t> order(sorted.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return sorted[a] < sorted[b]; });
    std::vector<char> keep(sorted.size(), 1);
    for (std::size_t k = 1; k < order.size(); ++k) {
        if (sorted[order[k]] == sorted[order[k - 1]]) {
            keep[order[k]] = 0;
            keep[order[k - 1]] = 0;
        }
    }

    CoarseMesh coarse;
    std::vector<Eigen::Index> coarse_of(static_cast<std::size_t>(mesh.V.rows()), -1);
    std::vector<int> faces_kept;
    for (std::size_t f = 0; f < sorted.size(); ++f) {
        if (!keep[f]) {
            continue;
        }
        for (std::size_t c = 0; c < 3; ++c) {
            const unsigned fine = simplified[3 * f + c];
            if (coarse_of[fine] < 0) {
                coarse_of[fine] = static_cast<Eigen::Index>(coarse.fine_vertex.size());
                coarse.fine_vertex.push_back(fine);
            }
            faces_kept.push_back(static_cast<int>(coarse_of[fine]));
        }
    }
    coarse.mesh.F = Eigen::Map<const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(
        faces_kept.data(), static_cast<Eigen::Index>(faces_kept.size() / 3), 3);
    coarse.mesh.V.resize(static_cast<Eigen::Index>(coarse.fine_vertex.size()), 3);
    for (std::size_t k = 0; k < coarse.fine_vertex.size(); ++k) {
        coarse.mesh.V.row(static_cast<Eigen::Index>(k)) = mesh.V.row(coarse.fine_vertex[k]);
    }
    return coarse;
}

namespace {

// The coarse mesh's faces as candidates for a fine vertex's embedding.
class CoarseFaces {
public:
    explicit CoarseFaces(const TriangleMesh& coarse)
        : coarse_(coarse),
          normals_(face_normals(coarse)),
          faces_at_(static_cast<std::size_t>(coarse.V.rows())) {
        for (Eigen::Index f = 0; f < coarse.F.rows(); ++f) {
            for (int c = 0; c < 3; ++c) {
                faces_at_[static_cast<std::size_t>(coarse.F(f, c))].push_back(static_cast<int>(f));
            }
        }
    }

    [[nodiscard]] const std::vector<int>& faces_at(Eigen::Index vertex) const {
        return faces_at_[static_cast<std::size_t>(vertex)];
    }

    [[nodiscard]] bool faces_along(Eigen::Index face, const Eigen::Vector3d& normal) const {
        return normals_.row(face).dot(normal) > 0;
    }

    // The point of `faces` nearest to p, among those facing along `normal` only if
    // `facing_only`; face −1 if there is none.
    [[nodiscard]] SurfacePoint closest(const Eigen::Vector3d& p, const Eigen::Vector3d& normal,
                                       const std::vector<int>& faces, bool facing_only) const {
        SurfacePoint best;
        best.distance = std::numeric_limits<double>::infinity();
        for (const int f : faces) {
            if (facing_only && !faces_along(f, normal)) {
                continue;
            }
            const Eigen::Vector3d w =
                closest_point_on_triangle(p, corner(f, 0), corner(f, 1), corner(f, 2));
            const Eigen::Vector3d q =
                w[0] * corner(f, 0) + w[1] * corner(f, 1) + w[2] * corner(f, 2);
            if ((q - p).norm() < best.distance) {
                best = {f, w, q, (q - p).norm()};
            }
        }
        return best;
    }

private:
    [[nodiscard]] Eigen::Vector3d corner(Eigen::Index f, int c) const {
        return coarse_.V.row(coarse_.F(f, c)).transpose();
    }

    const TriangleMesh& coarse_;
    Eigen::MatrixX3d normals_;
    std::vector<std::vector<int>> faces_at_;
};

// Per vertex of `mesh`, the vertices within `rings` edges of it (itself included), sorted.
std::vector<std::vector<Eigen::Index>> vertices_within(const TriangleMesh& mesh, int rings) {
    const std::vector<std::vector<Eigen::Index>> ring = vertex_neighbours(mesh.F, mesh.V.rows());
    std::vector<std::vector<Eigen::Index>> within(ring.size());
    for (std::size_t v = 0; v < within.size(); ++v) {
        std::vector<Eigen::Index>& near = within[v];
        near.push_back(static_cast<Eigen::Index>(v));
        for (int r = 0; r < rings; ++r) {
            const std::size_t inner = near.size();
            for (std::size_t k = 0; k < inner; ++k) {
                const std::vector<Eigen::Index>& next = ring[static_cast<std::size_t>(near[k])];
                near.insert(near.end(), next.begin(), next.end());
            }
            std::sort(near.begin(), near.end());
            near.erase(std::unique(near.begin(), near.end()), near.end());
        }
    }
    return within;
}

void set_row(Embedding& embedding, Eigen::Index i, const Eigen::Vector3d& p,
             const SurfacePoint& at) {
    embedding.face[i] = static_cast<int>(at.face);
    embedding.barycentric.row(i) = at.barycentric.transpose();
    embedding.offset.row(i) = (p - at.point).transpose();
}

}  // namespace

Embedding embed(const TriangleMesh& fine, const TriangleMesh& coarse) {
    detail::require_valid_mesh(fine, "embed");
    const TriangleBvh bvh(coarse);  // validates the coarse mesh
    const Eigen::MatrixX3d fine_normals = vertex_normals(fine);
    const CoarseFaces faces(coarse);
    // For the thin-part fallback: a point index of the coarse vertices.
    const detail::PointIndex vertices(coarse.V);

    const Eigen::Index n = fine.V.rows();
    Embedding e{Eigen::VectorXi(n), Eigen::MatrixX3d(n, 3), Eigen::MatrixX3d(n, 3)};
    std::vector<std::pair<std::uint32_t, double>> near;
    std::vector<int> candidates;
#pragma omp parallel for schedule(dynamic, 256) private(near, candidates)
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Vector3d p = fine.V.row(i).transpose();
        const Eigen::Vector3d normal = fine_normals.row(i).transpose();
        SurfacePoint best = bvh.closest_point(p);
        if (!faces.faces_along(best.face, normal) && normal.squaredNorm() > 0) {
            // The nearest face faces away (the other side of a thin part): look among the
            // faces around the coarse vertices within a few times that distance.
            vertices.within(p, std::pow(3 * best.distance + 1e-300, 2), near);
            candidates.clear();
            for (const auto& [v, unused] : near) {
                const std::vector<int>& around = faces.faces_at(v);
                candidates.insert(candidates.end(), around.begin(), around.end());
            }
            const SurfacePoint facing = faces.closest(p, normal, candidates, true);
            if (facing.face >= 0) {
                best = facing;
            }
        }
        set_row(e, i, p, best);
    }
    return e;
}

// How many coarse rings beyond the nearest coarse vertices the candidate faces reach: with one,
// 4 of the 2562 vertices of the generated limb missed their closest face (QEM leaves long
// triangles), with two none.
constexpr int kCoarseRings = 2;

Embedding embed(const TriangleMesh& fine, const CoarseMesh& coarse) {
    detail::require_valid_mesh(fine, "embed");
    detail::require_valid_mesh(coarse.mesh, "embed");
    if (coarse.mesh.F.rows() == 0) {
        throw InvalidInput("embed: the coarse mesh has no faces");
    }
    if (static_cast<Eigen::Index>(coarse.fine_vertex.size()) != coarse.mesh.V.rows() ||
        std::any_of(coarse.fine_vertex.begin(), coarse.fine_vertex.end(),
                    [&](Eigen::Index v) { return v < 0 || v >= fine.V.rows(); })) {
        throw InvalidInput(
            "embed: the coarse mesh's fine_vertex does not name a fine vertex "
            "for each coarse vertex");
    }
    // Which coarse vertex each fine one is nearest to along the fine surface: a hand resting on
    // a thigh is near the thigh in space, not along the surface.
    const detail::ChordGraph edges = detail::chord_graph(fine, 1);
    const std::vector<Eigen::Index> nearest = detail::nearest_sources(edges, coarse.fine_vertex);
    const std::vector<std::vector<Eigen::Index>> reach = vertices_within(coarse.mesh, kCoarseRings);
    const TriangleBvh bvh(coarse.mesh);
    const Eigen::MatrixX3d fine_normals = vertex_normals(fine);
    const CoarseFaces faces(coarse.mesh);

    const Eigen::Index n = fine.V.rows();
    Embedding e{Eigen::VectorXi(n), Eigen::MatrixX3d(n, 3), Eigen::MatrixX3d(n, 3)};
    std::vector<Eigen::Index> labels;
    std::vector<int> candidates;
    std::vector<char> placed(static_cast<std::size_t>(n), 0);
#pragma omp parallel for schedule(dynamic, 256) private(labels, candidates)
    for (Eigen::Index i = 0; i < n; ++i) {
        // The coarse vertices nearest to i and to its neighbours: the faces around them and
        // kCoarseRings further are every face of the surface near i, and none across a gap.
        labels.clear();
        labels.push_back(nearest[static_cast<std::size_t>(i)]);
        for (const detail::Chord& chord : edges[static_cast<std::size_t>(i)]) {
            labels.push_back(nearest[static_cast<std::size_t>(chord.vertex)]);
        }
        std::sort(labels.begin(), labels.end());
        labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
        if (labels.front() < 0) {
            continue;  // on a component without coarse vertices
        }
        const Eigen::Vector3d p = fine.V.row(i).transpose();
        const Eigen::Vector3d normal = fine_normals.row(i).transpose();
        const auto facing_right = [&](Eigen::Index f) {
            return faces.faces_along(f, normal) || normal.squaredNorm() == 0;
        };

        // Mostly the closest face of all is one of them, and facing the right way.
        SurfacePoint best = bvh.closest_point(p);
        const auto is_near = [&](Eigen::Index f) {
            for (const Eigen::Index label : labels) {
                const std::vector<Eigen::Index>& within = reach[static_cast<std::size_t>(label)];
                for (int c = 0; c < 3; ++c) {
                    if (std::binary_search(within.begin(), within.end(),
                                           Eigen::Index{coarse.mesh.F(f, c)})) {
                        return true;
                    }
                }
            }
            return false;
        };
        if (!is_near(best.face) || !facing_right(best.face)) {
            candidates.clear();
            for (const Eigen::Index label : labels) {
                for (const Eigen::Index v : reach[static_cast<std::size_t>(label)]) {
                    const std::vector<int>& at = faces.faces_at(v);
                    candidates.insert(candidates.end(), at.begin(), at.end());
                }
            }
            std::sort(candidates.begin(), candidates.end());
            candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
            if (candidates.empty()) {
                continue;  // near coarse vertices on no face
            }
            best = faces.closest(p, normal, candidates, false);
            if (!facing_right(best.face)) {
                // The nearest face faces away (the other side of a thin part).
                const SurfacePoint facing = faces.closest(p, normal, candidates, true);
                if (facing.face >= 0) {
                    best = facing;
                }
            }
        }
        set_row(e, i, p, best);
        placed[static_cast<std::size_t>(i)] = 1;
    }
    if (std::find(placed.begin(), placed.end(), 0) != placed.end()) {
        const Embedding anywhere = embed(fine, coarse.mesh);
        for (Eigen::Index i = 0; i < n; ++i) {
            if (placed[static_cast<std::size_t>(i)] == 0) {
                e.face[i] = anywhere.face[i];
                e.barycentric.row(i) = anywhere.barycentric.row(i);
                e.offset.row(i) = anywhere.offset.row(i);
            }
        }
    }
    return e;
}

TriangleMesh transfer(const TriangleMesh& fine_rest, const TriangleMesh& coarse_rest,
                      const Eigen::MatrixX3d& coarse_deformed, const Embedding& embedding) {
    const Eigen::Index n = fine_rest.V.rows();
    const Eigen::Index m = coarse_rest.V.rows();
    if (coarse_deformed.rows() != m || embedding.face.size() != n ||
        embedding.barycentric.rows() != n || embedding.offset.rows() != n) {
        throw InvalidInput("transfer: the embedding, meshes and positions have different sizes");
    }
    detail::require_valid_mesh(coarse_rest, "transfer");
    if (!detail::all_finite(coarse_deformed)) {
        throw InvalidInput("transfer: the deformed coarse positions are not finite");
    }
    for (Eigen::Index i = 0; i < n; ++i) {
        if (embedding.face[i] < 0 || embedding.face[i] >= coarse_rest.F.rows()) {
            throw InvalidInput("transfer: the embedding names a face the coarse mesh lacks");
        }
    }
    // One-ring rotation fits R_b, with the normal term h² n'_b n_bᵀ (docs/formulas.md §9).
    TriangleMesh deformed_coarse{coarse_deformed, coarse_rest.F};
    const Eigen::MatrixX3d n_rest = vertex_normals(coarse_rest);
    const Eigen::MatrixX3d n_deformed = vertex_normals(deformed_coarse);
    const double h = mean_edge_length(coarse_rest);
    std::vector<Eigen::Matrix3d> covariance(static_cast<std::size_t>(m));
    for (Eigen::Index b = 0; b < m; ++b) {
        covariance[static_cast<std::size_t>(b)] =
            h * h * n_deformed.row(b).transpose() * n_rest.row(b);
    }
    for (Eigen::Index f = 0; f < coarse_rest.F.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            const int a = coarse_rest.F(f, c);
            const int b = coarse_rest.F(f, (c + 1) % 3);
            // Each directed edge once per face: both ends see the other.
            const Eigen::Vector3d rest = (coarse_rest.V.row(b) - coarse_rest.V.row(a)).transpose();
            const Eigen::Vector3d moved =
                (coarse_deformed.row(b) - coarse_deformed.row(a)).transpose();
            covariance[static_cast<std::size_t>(a)] += moved * rest.transpose();
            covariance[static_cast<std::size_t>(b)] += moved * rest.transpose();
        }
    }
    std::vector<Eigen::Matrix3d> rotation(static_cast<std::size_t>(m));
    for (Eigen::Index b = 0; b < m; ++b) {
        rotation[static_cast<std::size_t>(b)] =
            detail::nearest_orthogonal(covariance[static_cast<std::size_t>(b)]);
    }
    TriangleMesh result = fine_rest;
    for (Eigen::Index i = 0; i < n; ++i) {
        const int f = embedding.face[i];
        Eigen::Vector3d base = Eigen::Vector3d::Zero();
        Eigen::Matrix3d blended = Eigen::Matrix3d::Zero();
        for (int c = 0; c < 3; ++c) {
            const int b = coarse_rest.F(f, c);
            const double w = embedding.barycentric(i, c);
            base += w * coarse_deformed.row(b).transpose();
            blended += w * rotation[static_cast<std::size_t>(b)];
        }
        result.V.row(i) =
            (base + detail::nearest_orthogonal(blended) * embedding.offset.row(i).transpose())
                .transpose();
    }
    return result;
}

}  // namespace genflow
