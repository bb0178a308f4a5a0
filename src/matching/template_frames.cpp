// SPDX-License-Identifier: MIT
#include "genflow/matching/template_frames.h"

#include <algorithm>

#include "genflow/exceptions.h"
#include "operators/triangle.h"

namespace genflow {

TemplateFrames::TemplateFrames(TriangleMesh template_mesh) : template_(std::move(template_mesh)) {
    detail::require_valid_mesh(template_, "TemplateFrames");
}

TriangleMesh TemplateFrames::operator()(const TriangleMesh& level_mesh,
                                        const std::vector<Eigen::Index>& template_vertex) {
    const Eigen::Index count = template_.V.rows();
    const bool fits = static_cast<Eigen::Index>(template_vertex.size()) == level_mesh.V.rows() &&
                      std::all_of(template_vertex.begin(), template_vertex.end(),
                                  [count](Eigen::Index v) { return v >= 0 && v < count; });
    if (!fits) {
        throw InvalidInput("TemplateFrames: the level's vertices must each name a template vertex");
    }
    if (level_mesh.V.rows() == count && level_mesh.F == template_.F) {
        return level_mesh;
    }
    auto found = levels_.find(template_vertex);
    if (found == levels_.end()) {
        CoarseMesh coarse{TriangleMesh{template_.V(template_vertex, Eigen::all), level_mesh.F},
                          template_vertex};
        Embedding embedding = embed(template_, coarse);
        found =
            levels_.emplace(template_vertex, Level{std::move(coarse.mesh), std::move(embedding)})
                .first;
    }
    const Level& level = found->second;
    return transfer(template_, level.rest, level_mesh.V, level.embedding);
}

}  // namespace genflow
