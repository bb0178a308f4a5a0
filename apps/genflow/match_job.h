// SPDX-License-Identifier: MIT
// One matching job as `genflow match` and `genflow demo` run it: match, then write the deformed
// template, the correspondences, the frames and the JSON summary.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli_support.h"
#include "genflow/io/vertex_attributes.h"
#include "genflow/matching/match.h"

namespace genflow::cli {

struct MatchJob {
    TriangleMesh template_mesh;
    TriangleMesh target;
    std::string template_name;  ///< for the summary
    std::string target_name;
    Eigen::Index target_points = 0;  ///< where the target was a point cloud, its points
    bool target_normals = false;     ///< whether the point cloud came with normals
    std::filesystem::path output;    ///< the deformed template
    std::optional<std::filesystem::path> correspondence;  ///< per-vertex closest target points
    /// Animation frames: the template at its own resolution after every frame_every-th step.
    std::optional<std::filesystem::path> frames;
    int frame_every = 1;
    std::optional<std::filesystem::path> summary;  ///< the JSON summary, as a file
    /// The deformed template coloured by its error (with a ground truth) or its distance to the
    /// target, per vertex.
    std::optional<std::filesystem::path> colored;
    /// An HTML page showing the run (match_report()).
    std::optional<std::filesystem::path> report;
    /// Known positions of the template's vertices on the target (a generated pair): the
    /// summary then reports the correspondence error.
    std::optional<Eigen::MatrixX3d> ground_truth;
    /// What the template's file gives per vertex and goes with it onto the target (colours,
    /// values; carried_attributes()), written with the deformed template.
    VertexAttributes template_attributes;
    MatchOptions options;
    bool progress_bar = true;
};

/// A job matching `template_mesh` onto `target` as loaded from their files, named by their
/// paths, the template's attributes carried (carried_attributes()); outputs and options are the
/// caller's. `quiet`: no progress bar and no warnings.
[[nodiscard]] MatchJob match_job_for(const LoadedMesh& template_mesh, const LoadedMesh& target,
                                     bool quiet);

/// Runs the job and returns its summary (also written to job.summary when set). Outputs are
/// written atomically, only after the match succeeded. The output holds the template's
/// attributes and, per vertex, the deformed template's distance to the target ("distance")
/// and, with a ground truth, its correspondence error ("error"), both as lengths (values of
/// the template's of the same names are replaced, with a warning).
nlohmann::json run_match_job(MatchJob job);

}  // namespace genflow::cli
