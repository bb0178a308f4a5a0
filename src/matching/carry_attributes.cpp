// SPDX-License-Identifier: MIT
#include "genflow/matching/carry_attributes.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "genflow/exceptions.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

bool is_label(const Eigen::VectorXd& values) {
    return std::all_of(values.data(), values.data() + values.size(),
                       [](double v) { return v == std::round(v); });
}

void check_rows(const TriangleMesh& template_mesh, const VertexAttributes& attributes,
                const std::vector<SurfacePoint>& correspondence) {
    const Eigen::Index n = template_mesh.V.rows();
    const Eigen::MatrixX3i& corners = attributes.corner_uv_faces;
    bool fits = static_cast<Eigen::Index>(correspondence.size()) == n &&
                (attributes.colors.rows() == 0 || attributes.colors.rows() == n) &&
                (attributes.uvs.rows() == 0 || attributes.uvs.rows() == n) &&
                (corners.rows() == 0 ||
                 (corners.rows() == template_mesh.F.rows() && corners.minCoeff() >= 0 &&
                  corners.maxCoeff() < attributes.corner_uvs.rows()));
    for (const auto& [name, values] : attributes.scalars) {
        fits = fits && values.size() == n;
    }
    if (!fits) {
        throw InvalidInput(
            "carry_attributes: the correspondence and the attributes need a row "
            "per template vertex (" +
            std::to_string(n) + "), texture coordinates per corner a row per face");
    }
}

// The texture coordinates at a point of template face `face` (barycentric `weights`): from
// the face's corners, per corner where the template has them so (the face's own side of a
// seam), else per vertex.
Eigen::RowVector2d texture_at(const TriangleMesh& template_mesh, const VertexAttributes& attributes,
                              Eigen::Index face, const Eigen::Vector3d& weights) {
    Eigen::RowVector2d uv = Eigen::RowVector2d::Zero();
    for (int k = 0; k < 3; ++k) {
        uv += weights[k] * (attributes.corner_uv_faces.rows() > 0
                                ? attributes.corner_uvs.row(attributes.corner_uv_faces(face, k))
                                : attributes.uvs.row(template_mesh.F(face, k)));
    }
    return uv;
}

}  // namespace

VertexAttributes carry_attributes(const TriangleMesh& template_mesh,
                                  const VertexAttributes& attributes, const TriangleMesh& target,
                                  const std::vector<SurfacePoint>& correspondence) {
    detail::require_valid_mesh(template_mesh, "carry_attributes");
    detail::require_valid_mesh(target, "carry_attributes");
    check_rows(template_mesh, attributes, correspondence);
    TriangleMesh laid_over{positions_of(correspondence), template_mesh.F};
    const TriangleBvh bvh(laid_over);
    const Eigen::Index count = target.V.rows();
    VertexAttributes carried;
    const bool has_colors = attributes.colors.rows() > 0;
    if (has_colors) {
        carried.colors.resize(count, 3);
    }
    const bool has_texture = attributes.uvs.rows() > 0 || attributes.corner_uv_faces.rows() > 0;
    if (has_texture) {
        carried.uvs.resize(count, 2);
    }
    for (const auto& [name, values] : attributes.scalars) {
        carried.scalars.emplace_back(name, Eigen::VectorXd(count));
    }
    std::vector<bool> label;
    for (const auto& [name, values] : attributes.scalars) {
        label.push_back(is_label(values));
    }
#pragma omp parallel for schedule(dynamic, 256)
    for (Eigen::Index t = 0; t < count; ++t) {
        const SurfacePoint under = bvh.closest_point(target.V.row(t).transpose());
        const Eigen::RowVector3i corners = template_mesh.F.row(under.face);
        int nearest = 0;
        under.barycentric.maxCoeff(&nearest);
        if (has_colors) {
            for (int c = 0; c < 3; ++c) {
                double value = 0;
                for (int k = 0; k < 3; ++k) {
                    value += under.barycentric[k] * attributes.colors(corners[k], c);
                }
                carried.colors(t, c) =
                    static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 255.0)));
            }
        }
        if (has_texture) {
            carried.uvs.row(t) =
                texture_at(template_mesh, attributes, under.face, under.barycentric);
        }
        for (std::size_t s = 0; s < carried.scalars.size(); ++s) {
            const Eigen::VectorXd& values = attributes.scalars[s].second;
            double value = values[corners[nearest]];
            if (!label[s]) {
                value = 0;
                for (int k = 0; k < 3; ++k) {
                    value += under.barycentric[k] * values[corners[k]];
                }
            }
            carried.scalars[s].second[t] = value;
        }
    }
    return carried;
}

}  // namespace genflow
