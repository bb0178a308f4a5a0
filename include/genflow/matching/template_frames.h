// SPDX-License-Identifier: MIT
#pragma once

#include <map>
#include <vector>

#include "genflow/matching/multiresolution.h"

namespace genflow {

/// The frames of a match at the template's own resolution: a level's deformed template
/// (MatchProgress::mesh, whose vertex k is template vertex template_vertex[k]) carried to every
/// vertex of the template by transfer(), so that the frames of all levels have one vertex count
/// and one set of faces and play as one animation. Each level is embedded once, when its first
/// frame comes.
class TemplateFrames {
public:
    /// \throws InvalidInput if the template has no face, bad indices or non-finite coordinates.
    explicit TemplateFrames(TriangleMesh template_mesh);

    /// The template deformed as `level_mesh` is: `level_mesh` itself at the template's
    /// resolution, else its motion carried to the template.
    /// \throws InvalidInput if `template_vertex` does not name a template vertex for each vertex
    ///         of `level_mesh`.
    [[nodiscard]] TriangleMesh operator()(const TriangleMesh& level_mesh,
                                          const std::vector<Eigen::Index>& template_vertex);

private:
    struct Level {
        TriangleMesh rest;  ///< the level's vertices where the template has them
        Embedding embedding;
    };
    TriangleMesh template_;
    std::map<std::vector<Eigen::Index>, Level> levels_;  ///< by their template vertices
};

}  // namespace genflow
