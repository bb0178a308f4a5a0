// SPDX-License-Identifier: MIT
// match(): a template deformed onto a target, with the progress of every step in Python and
// Ctrl-C stopping it; the part models of the articulated prior, and the template cache of a
// batch.
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "genflow/exceptions.h"
#include "genflow/io/read_part_model.h"
#include "genflow/matching/correspondence.h"
#include "genflow/matching/match.h"

namespace py = pybind11;

namespace genflow::python {

namespace {

MatchPrior prior_named(const std::string& name) {
    if (const auto prior = parse_match_prior(name)) {
        return *prior;
    }
    std::string names;
    for (const std::string& known : match_prior_names()) {
        names += (names.empty() ? "'" : ", '") + known + "'";
    }
    throw InvalidInput("match: prior must be one of " + names + ", got '" + name + "'");
}

// A part model from its parts (names, parent indices, −1 for a root, joint centres as rows) and
// its weights (a row per template vertex, a column per part).
PartModel part_model_of(const std::vector<std::string>& names, const std::vector<int>& parents,
                        const Eigen::Ref<const RowMatrixX3d>& joint_centres,
                        const Eigen::Ref<const Eigen::MatrixXd>& weights) {
    const auto count = names.size();
    if (parents.size() != count || static_cast<std::size_t>(joint_centres.rows()) != count) {
        throw InvalidInput(
            "PartModel: names, parents and joint_centres must have a row per part (" +
            std::to_string(count) + " names, " + std::to_string(parents.size()) + " parents, " +
            std::to_string(joint_centres.rows()) + " joint centres)");
    }
    PartModel model;
    for (std::size_t p = 0; p < count; ++p) {
        model.parts.push_back(
            {names[p], parents[p], joint_centres.row(static_cast<Eigen::Index>(p)).transpose()});
    }
    model.weights = weights;
    check_part_model(model, weights.rows());
    return model;
}

PartModel read_part_model_of(const std::string& tree, Eigen::Index vertices,
                             const std::optional<std::string>& labels,
                             const std::optional<std::string>& weights, const std::string& pose,
                             const std::string& template_name) {
    PartFiles files{.tree = tree, .pose = pose, .template_name = template_name};
    if (labels) {
        files.labels = *labels;
    }
    if (weights) {
        files.weights = *weights;
    }
    return read_part_model(files, vertices);
}

void bind_part_model(py::module_& module) {
    py::class_<PartModel>(module, "PartModel",
                          "The parts of a template for the articulated prior: a tree of parts with "
                          "their joint centres, and a weight per template vertex and part.")
        .def(py::init(&part_model_of), py::arg("names"), py::arg("parents"),
             py::arg("joint_centres"), py::arg("weights"),
             "names and parents (index of each part's parent, -1 for a root) per part, "
             "joint_centres (#parts x 3), weights (#V x #parts, rows summing to 1). Checked.")
        .def_property_readonly("names",
                               [](const PartModel& model) {
                                   std::vector<std::string> names;
                                   for (const Part& part : model.parts) {
                                       names.push_back(part.name);
                                   }
                                   return names;
                               })
        .def_property_readonly("parents",
                               [](const PartModel& model) {
                                   std::vector<int> parents;
                                   for (const Part& part : model.parts) {
                                       parents.push_back(part.parent);
                                   }
                                   return parents;
                               })
        .def_property_readonly("weights", [](const PartModel& model) { return model.weights; });
    module.def("read_part_model", &read_part_model_of, py::arg("tree"), py::arg("vertices"),
               py::arg("labels") = py::none(), py::arg("weights") = py::none(),
               py::arg("pose") = "", py::arg("template_name") = "",
               "Reads a part model for a template of `vertices` vertices, as genflow match "
               "--parts does: the part tree (JSON), and the part of each vertex (labels) or "
               "weights per vertex, unless the tree names its file; pose: the template's pose "
               "among the file's.");
}

void bind_template_cache(py::module_& module) {
    py::class_<TemplateCache, std::shared_ptr<TemplateCache>>(
        module, "TemplateCache",
        "What match() computes of a template alone (its repair, coarser levels, eigenbases, "
        "signatures), kept for the next match of the same template: give one to every match of "
        "a batch. The results are those without it.")
        .def(py::init<>())
        .def("__len__", &TemplateCache::size, "How many analyses it holds.");
}

// The extent named as the command line's --target-extent names it.
TargetExtent extent_named(const std::string& name) {
    if (const auto extent = parse_target_extent(name)) {
        return *extent;
    }
    throw InvalidInput("match: target_extent must be 'auto', 'complete' or 'partial', got '" +
                       name + "'");
}

// Landmarks as rows "template vertex, x, y, z" (#L×4) and an optional weight per row.
LandmarkOptions landmarks_of(const std::optional<Eigen::MatrixX4d>& rows, double weight) {
    LandmarkOptions landmarks;
    landmarks.weight = weight;
    if (!rows) {
        return landmarks;
    }
    for (Eigen::Index r = 0; r < rows->rows(); ++r) {
        const double vertex = (*rows)(r, 0);
        if (!(vertex >= 0) || vertex != std::floor(vertex)) {
            throw InvalidInput("match: a landmark's first column is a template vertex index, got " +
                               std::to_string(vertex));
        }
        landmarks.points.push_back(
            {static_cast<Eigen::Index>(vertex), rows->row(r).tail<3>().transpose(), 1.0});
    }
    return landmarks;
}

// The match's levels and choices as Python values.
py::list levels_of(const MatchResult& result) {
    py::list levels;
    for (const MatchLevel& level : result.levels) {
        py::dict entry;
        entry["template_vertices"] = level.template_vertices;
        entry["target_vertices"] = level.target_vertices;
        entry["iterations"] = level.iterations;
        entry["status"] = to_string(level.status);
        entry["pseudo_hausdorff_per_step"] = level.energy;
        entry["seconds"] = level.seconds;
        levels.append(entry);
    }
    return levels;
}

py::dict result_dict(const MatchResult& result, const TriangleMesh& target) {
    const std::vector<SurfacePoint> points = match_correspondence(result, target);
    Eigen::VectorXi faces(static_cast<Eigen::Index>(points.size()));
    RowMatrixX3d barycentric(faces.size(), 3);
    RowMatrixX3d positions(faces.size(), 3);
    for (Eigen::Index i = 0; i < faces.size(); ++i) {
        const SurfacePoint& p = points[static_cast<std::size_t>(i)];
        faces[i] = static_cast<int>(p.face);
        barycentric.row(i) = p.barycentric.transpose();
        positions.row(i) = p.point.transpose();
    }
    py::dict out;
    out["V"] = RowMatrixX3d(result.deformed.V);
    out["correspondence"] = py::dict(py::arg("faces") = faces, py::arg("barycentric") = barycentric,
                                     py::arg("points") = positions);
    out["converged"] = result.converged();
    out["pseudo_hausdorff"] = result.hausdorff_energy;
    out["levels"] = levels_of(result);
    out["seconds"] = result.seconds;
    out["partial_target"] = result.partial_target;
    return out;
}

// The keyword arguments of match() beside the meshes, the callback and the landmarks.
struct MatchArguments {
    std::string prior;
    int iterations;
    int fine_iterations;
    int levels;
    Eigen::Index coarse_vertices;
    double alpha;
    double max_step;
    bool align;
    std::string target_extent;
};

MatchOptions options_of(const MatchArguments& a) {
    MatchOptions options;
    options.prior = prior_named(a.prior);
    options.max_iterations = a.iterations;
    options.fine_iterations = a.fine_iterations;
    options.levels = a.levels;
    options.coarse_vertices = a.coarse_vertices;
    options.alpha = a.alpha;
    options.max_step = a.max_step;
    options.starts.enabled = a.align;
    options.partial.extent = extent_named(a.target_extent);
    return options;
}

py::dict match_of(const Eigen::Ref<const RowMatrixX3d>& V, const Eigen::Ref<const RowMatrixX3i>& F,
                  const Eigen::Ref<const RowMatrixX3d>& VT,
                  const Eigen::Ref<const RowMatrixX3i>& FT, const std::string& prior,
                  int iterations, int fine_iterations, int levels, Eigen::Index coarse_vertices,
                  double alpha, double max_step, bool align, const std::string& target_extent,
                  const std::optional<Eigen::MatrixX4d>& landmarks, double landmark_weight,
                  const std::function<bool(py::dict)>& progress,
                  const std::optional<PartModel>& parts,
                  const std::shared_ptr<TemplateCache>& template_cache) {
    const TriangleMesh template_mesh = mesh_of(V, F);
    const TriangleMesh target = mesh_of(VT, FT);
    MatchOptions options = options_of({prior, iterations, fine_iterations, levels, coarse_vertices,
                                       alpha, max_step, align, target_extent});
    options.parts = parts;
    options.template_cache = template_cache;
    options.landmarks = landmarks_of(landmarks, landmark_weight);
    // The match runs without the GIL; each step takes it back to look for Ctrl-C and to call
    // `progress`: an exception from either (KeyboardInterrupt, or whatever `progress` raised)
    // or progress's False stops the match where it is, and the exception is raised once it has
    // returned.
    std::optional<py::error_already_set> failure;
    bool stopped = false;
    options.progress = [&](const MatchProgress& p) {
        if (failure || stopped) {
            return false;
        }
        const py::gil_scoped_acquire gil;
        try {
            if (PyErr_CheckSignals() != 0) {
                throw py::error_already_set();
            }
            stopped = progress &&
                      !progress(py::dict(py::arg("level") = p.levels - p.level,
                                         py::arg("levels") = p.levels, py::arg("step") = p.step,
                                         py::arg("max_steps") = p.max_steps,
                                         py::arg("pseudo_hausdorff") = p.energy));
        } catch (py::error_already_set& error) {
            failure = std::move(error);
        }
        return !failure && !stopped;
    };
    MatchResult result;
    {
        const py::gil_scoped_release released;
        result = match(template_mesh, target, options);
    }
    if (failure) {
        throw *failure;
    }
    return result_dict(result, target);
}

}  // namespace

void bind_match(py::module_& module) {
    bind_part_model(module);
    bind_template_cache(module);
    const MatchOptions defaults;
    module.def(
        "match", &match_of, py::arg("V"), py::arg("F"), py::arg("V_target"), py::arg("F_target"),
        py::arg("prior") = "h1", py::arg("iterations") = defaults.max_iterations,
        py::arg("fine_iterations") = defaults.fine_iterations, py::arg("levels") = defaults.levels,
        py::arg("coarse_vertices") = defaults.coarse_vertices, py::arg("alpha") = defaults.alpha,
        py::arg("max_step") = defaults.max_step, py::arg("align") = defaults.starts.enabled,
        py::arg("target_extent") = to_string(defaults.partial.extent),
        py::arg("landmarks") = py::none(), py::arg("landmark_weight") = defaults.landmarks.weight,
        py::arg("progress") = nullptr, py::arg("parts") = py::none(),
        py::arg("template_cache") = nullptr,
        "Deforms the template (V, F) onto the target as genflow match does, with the "
        "prior 'l2', 'h1', 'rigid', 'articulated' (needs parts, a PartModel) or "
        "'isometric'. iterations: steps of each coarsest flow; fine_iterations: of each "
        "finer one; levels (0: chosen), the coarsest about coarse_vertices; alpha: d_H's "
        "exponent; max_step: a step's longest move over the target's diagonal; align: "
        "rigid starts (False: from the frames as placed); target_extent 'auto', "
        "'complete' or 'partial'. landmarks: rows (template vertex, x, y, z). progress(dict) is "
        "called after every step (level, levels, step, "
        "max_steps, pseudo_hausdorff); returning False stops the match. Ctrl-C stops it "
        "with KeyboardInterrupt. template_cache: a TemplateCache shared by the matches of "
        "one template. Returns a dict: V (the deformed template), correspondence (faces, "
        "barycentric, points on the target per template vertex), converged, "
        "pseudo_hausdorff, levels, seconds, partial_target.");
}

}  // namespace genflow::python
