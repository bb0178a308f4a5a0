// SPDX-License-Identifier: MIT
#include "match_job.h"

#include <iostream>
#include <vector>

#include "cli_support.h"
#include "frame_sink.h"
#include "genflow/exceptions.h"
#include "genflow/io/atomic_file.h"
#include "genflow/io/color_map.h"
#include "genflow/io/write_correspondences.h"
#include "genflow/io/write_mesh.h"
#include "genflow/matching/correspondence.h"
#include "genflow/matching/correspondence_error.h"
#include "genflow/matching/template_frames.h"
#include "genflow/mesh/repair.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/spatial/surface_distance.h"
#include "genflow/version.h"
#include "progress_bar.h"
#include "reports.h"

namespace genflow::cli {

namespace {

// The deformed template's values per vertex, written with it: its distance to the target's
// surface, and with a ground truth its distance from where the vertex belongs.
VertexAttributes vertex_values(const MatchJob& job, const TriangleMesh& deformed) {
    VertexAttributes values = job.template_attributes;
    std::erase_if(values.scalars, [&](const auto& value) {
        const bool replaced = value.first == "distance" || value.first == "error";
        if (replaced && job.progress_bar) {
            std::cerr << "warning: " << printable(job.template_name) << ": its vertex value '"
                      << printable(value.first) << "' is replaced by the match's\n";
        }
        return replaced;
    });
    for (auto& value :
         result_values(deformed, job.target, job.ground_truth ? &*job.ground_truth : nullptr)) {
        values.scalars.push_back(std::move(value));
    }
    return values;
}

// The colours of --colored: the last of `values` (the error where there is one) on viridis,
// from 0 to its largest value (or the target's diagonal if that is 0); the scale goes in the
// summary.
VertexAttributes colored_by_last(VertexAttributes values, double diagonal,
                                 nlohmann::json& summary) {
    const auto& [name, field] = values.scalars.back();
    const double top = field.maxCoeff() > 0 ? field.maxCoeff() : diagonal;
    values.colors = viridis_colors(field, 0, top);
    summary["colored"] = {{"property", name}, {"color_map", "viridis"}, {"scale", {0.0, top}}};
    return values;
}

}  // namespace

MatchJob match_job_for(const LoadedMesh& template_mesh, const LoadedMesh& target, bool quiet) {
    MatchJob job;
    job.template_mesh = template_mesh.mesh;
    job.template_attributes = carried_attributes(template_mesh, quiet);
    job.target = target.mesh;
    job.template_name = template_mesh.path.string();
    job.target_name = target.path.string();
    job.target_points = target.points;
    job.target_normals = target.normals;
    job.progress_bar = !quiet;
    return job;
}

nlohmann::json run_match_job(MatchJob job) {
    int frame = 0;
    FrameSink sink(job.frames);
    std::optional<TemplateFrames> frames;
    if (sink.active()) {
        frames.emplace(repair_surface(job.template_mesh).mesh);  // as match() flows it
    }
    ProgressBar bar("match", job.progress_bar);
    job.options.progress = [&](const MatchProgress& p) {
        bar.update(p.step, p.max_steps,
                   "level " + std::to_string(p.levels - p.level) + "/" + std::to_string(p.levels) +
                       ", d_H " + std::to_string(p.energy));
        if (frames && (p.step % job.frame_every == 0 || p.step == p.max_steps)) {
            sink.add((*frames)(*p.mesh, *p.template_vertex), frame++);
        }
        return true;
    };
    // With a ground truth, the error after each stage of each level.
    nlohmann::json stages = nlohmann::json::array();
    const double truth_diagonal =
        job.ground_truth
            ? bounding_box_diagonal(TriangleMesh{*job.ground_truth, job.template_mesh.F})
            : 0;
    if (job.ground_truth) {
        job.options.stages =
            stage_errors(job.template_mesh, *job.ground_truth, truth_diagonal, stages);
    }
    const MatchResult result = match(job.template_mesh, job.target, job.options);
    bar.finish();

    const SurfaceDistances distances = surface_distances(result.deformed, job.target);
    const double diagonal = bounding_box_diagonal(job.target);
    nlohmann::json levels = nlohmann::json::array();
    for (const MatchLevel& level : result.levels) {
        levels.push_back({{"template_vertices", level.template_vertices},
                          {"target_vertices", level.target_vertices},
                          {"iterations", level.iterations},
                          {"status", to_string(level.status)},
                          {"pseudo_hausdorff_start", level.energy_start},
                          {"pseudo_hausdorff_end", level.energy_end},
                          {"pseudo_hausdorff_per_step", level.energy},
                          {"seconds", level.seconds}});
    }
    const Eigen::Matrix4d alignment = result.initial_alignment.matrix();
    nlohmann::json summary = {
        {"genflow", std::string(kVersion)},
        {"command_line", command_line()},  // every option, as given
        {"template", job.template_name},
        {"target", job.target_name},
        {"output", job.output.string()},
        {"prior", to_string(job.options.prior)},
        {"converged", result.converged()},
        {"levels", levels},
        {"alignment_seconds", result.alignment_seconds},
        {"seconds", result.seconds},
        {"stage_times", stage_times_json(result)},
        {"initial_alignment",
         {{alignment(0, 0), alignment(0, 1), alignment(0, 2), alignment(0, 3)},
          {alignment(1, 0), alignment(1, 1), alignment(1, 2), alignment(1, 3)},
          {alignment(2, 0), alignment(2, 1), alignment(2, 2), alignment(2, 3)},
          {0, 0, 0, 1}}},
        {"pseudo_hausdorff", result.hausdorff_energy},
        {"template_repairs", result.template_repairs},
        {"target_repairs", result.target_repairs},
        {"hausdorff", distances.hausdorff},
        {"mean_distance", distances.mean},
        {"target_bbox_diagonal", diagonal},
        {"hausdorff_over_diagonal", distances.hausdorff / diagonal},
        {"mean_distance_over_diagonal", distances.mean / diagonal},
    };
    summary.update(match_choices(result));
    summary["landmarks"] = job.options.landmarks.points.size();
    summary["target_points"] =
        job.target_points > 0 ? nlohmann::json(job.target_points) : nlohmann::json(nullptr);
    summary["target_normals"] = job.target_normals;
    if (job.ground_truth) {
        // Over the ground truth's own diagonal (the target's surface, sampled as the template).
        const CorrespondenceError error = correspondence_error(
            result.deformed.V, TriangleMesh{*job.ground_truth, result.deformed.F});
        summary["correspondence_error_over_diagonal"] = {
            {"mean", error.mean}, {"median", error.median}, {"max", error.max}};
        summary["stranded_vertices"] = error.stranded_count;
        summary["reversed_area"] = error.reversed_area;
        // Which ones, so that they can be shown on the mesh (0-based template indices).
        std::vector<Eigen::Index> stranded;
        for (std::size_t i = 0; i < error.stranded.size(); ++i) {
            if (error.stranded[i]) {
                stranded.push_back(static_cast<Eigen::Index>(i));
            }
        }
        summary["stranded_vertex_indices"] = stranded;
        summary["stages"] = stages;
    }

    // All or none: a failure at the last file leaves the earlier ones as they were.
    OutputTransaction outputs;
    const VertexAttributes values = vertex_values(job, result.deformed);
    write_mesh_with(job.output, result.deformed, values, !job.progress_bar);
    if (job.colored) {
        write_mesh(*job.colored, result.deformed, colored_by_last(values, diagonal, summary));
        summary["colored"]["file"] = job.colored->string();
    }
    if (job.correspondence) {
        write_correspondences(*job.correspondence, match_correspondence(result, job.target));
        summary["correspondence"] = job.correspondence->string();
    }
    // The animation goes with the repaired template's vertices, which its own colours need not.
    sink.finish({});
    if (job.report) {
        summary["report"] = job.report->string();
        write_html_report(*job.report, match_report(job, result, values, summary));
    }
    if (job.summary) {
        write_file_atomically(*job.summary, summary.dump(2) + "\n");
    }
    outputs.commit();
    return summary;
}

}  // namespace genflow::cli
