// SPDX-License-Identifier: MIT
#include "io/attribute_checks.h"

#include <algorithm>
#include <string>

#include "genflow/exceptions.h"
#include "operators/triangle.h"

namespace genflow::detail {

namespace {

bool is_ply_name(const std::string& name) {
    return !name.empty() && std::none_of(name.begin(), name.end(), [](char c) {
        return static_cast<unsigned char>(c) <= ' ' || c == 0x7f;
    });
}

}  // namespace

void check_face_indices(const std::string& who, const Eigen::MatrixX3i& faces,
                        Eigen::Index vertices) {
    if (faces.size() > 0 && (faces.minCoeff() < 0 || faces.maxCoeff() >= vertices)) {
        throw InvalidInput(who + ": face indices must lie in [0, " + std::to_string(vertices) +
                           ")");
    }
}

void check_attributes(const std::filesystem::path& path, const TriangleMesh& mesh,
                      const VertexAttributes& attributes) {
    if (attributes.colors.rows() != 0 && attributes.colors.rows() != mesh.V.rows()) {
        throw InvalidInput(path.string() + ": " + std::to_string(attributes.colors.rows()) +
                           " vertex colours for " + std::to_string(mesh.V.rows()) + " vertices");
    }
    if (attributes.normals.rows() != 0 &&
        (attributes.normals.rows() != mesh.V.rows() || !detail::all_finite(attributes.normals))) {
        throw InvalidInput(path.string() + ": vertex normals need a finite row per vertex");
    }
    if (attributes.uvs.rows() != 0 &&
        (attributes.uvs.rows() != mesh.V.rows() || !detail::all_finite(attributes.uvs))) {
        throw InvalidInput(path.string() + ": texture coordinates need a finite row per vertex");
    }
    const Eigen::MatrixX3i& corners = attributes.corner_uv_faces;
    const bool no_corners = corners.rows() == 0 && attributes.corner_uvs.rows() == 0;
    if (!no_corners &&
        (corners.rows() == 0 || corners.rows() != mesh.F.rows() || corners.minCoeff() < 0 ||
         corners.maxCoeff() >= attributes.corner_uvs.rows() ||
         !detail::all_finite(attributes.corner_uvs))) {
        throw InvalidInput(path.string() +
                           ": texture coordinates per corner need a row of table indices per "
                           "face and finite coordinates");
    }
    for (const auto& [name, values] : attributes.scalars) {
        if (!is_ply_name(name) || name == "x" || name == "y" || name == "z" || name == "nx" ||
            name == "ny" || name == "nz" || name == "red" || name == "green" || name == "blue") {
            throw InvalidInput(path.string() +
                               ": a vertex value needs a name of its own without "
                               "spaces, got \"" +
                               name + "\"");
        }
        if (values.size() != mesh.V.rows() || !detail::all_finite(values)) {
            throw InvalidInput(path.string() + ": vertex value " + name +
                               " needs a finite number per vertex");
        }
    }
}

}  // namespace genflow::detail
