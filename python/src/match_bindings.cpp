// SPDX-License-Identifier: MIT
// match(): a template deformed onto a target, with the progress of every step in Python and
// Ctrl-C stopping it.
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <optional>

#include "bindings.h"
#include "genflow/exceptions.h"
#include "genflow/matching/correspondence.h"
#include "genflow/matching/match.h"

namespace py = pybind11;

namespace genflow::python {

namespace {

MatchPrior prior_named(const std::string& name) {
    if (const auto prior = parse_match_prior(name)) {
        return *prior;
    }
    throw InvalidInput(
        "match: prior must be 'l2', 'h1', 'rigid', 'articulated' or 'isometric', "
        "got '" +
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

py::dict match_of(const Eigen::Ref<const RowMatrixX3d>& V, const Eigen::Ref<const RowMatrixX3i>& F,
                  const Eigen::Ref<const RowMatrixX3d>& VT,
                  const Eigen::Ref<const RowMatrixX3i>& FT, const std::string& prior,
                  int iterations, double alpha, const std::optional<Eigen::MatrixX4d>& landmarks,
                  double landmark_weight, const std::function<bool(py::dict)>& progress) {
    const TriangleMesh template_mesh = mesh_of(V, F);
    const TriangleMesh target = mesh_of(VT, FT);
    MatchOptions options;
    options.prior = prior_named(prior);
    options.max_iterations = iterations;
    options.alpha = alpha;
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
    module.def("match", &match_of, py::arg("V"), py::arg("F"), py::arg("V_target"),
               py::arg("F_target"), py::arg("prior") = "h1", py::arg("iterations") = 300,
               py::arg("alpha") = 8.0, py::arg("landmarks") = py::none(),
               py::arg("landmark_weight") = 10.0, py::arg("progress") = nullptr,
               "Deforms the template (V, F) onto the target as genflow match does, with the "
               "prior 'l2', 'h1', 'rigid' or 'isometric' ('articulated' needs a part model, not "
               "yet here), up to `iterations` steps a level. landmarks: rows (template vertex, "
               "x, y, z). progress(dict) is called after every step (level, levels, step, "
               "max_steps, pseudo_hausdorff); returning False stops the match. Ctrl-C stops it "
               "with KeyboardInterrupt. Returns a dict: V (the deformed template), "
               "correspondence (faces, barycentric, points on the target per template vertex), "
               "converged, pseudo_hausdorff, levels, seconds, partial_target.");
}

}  // namespace genflow::python
