// SPDX-License-Identifier: MIT
// The smoothing flows of genflow/smoothing/smoothing.h, interruptible with Ctrl-C.
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <optional>

#include "bindings.h"
#include "genflow/exceptions.h"
#include "genflow/smoothing/smoothing.h"

namespace py = pybind11;

namespace genflow::python {

namespace {

// The flow runs without the GIL; each step takes it back to look for Ctrl-C (or another
// signal's exception), which stops the flow and is raised once it has returned.
py::tuple smooth(const Eigen::Ref<const RowMatrixX3d>& V, const Eigen::Ref<const RowMatrixX3i>& F,
                 const std::string& method, int steps, double time_step,
                 std::optional<double> lambda, double volume_lambda, bool fix_boundary,
                 bool freeze_metric) {
    const SmoothingFlow& flow = smoothing_flow(method);
    const TriangleMesh mesh = mesh_of(V, F);
    SmoothingOptions options;
    options.steps = steps;
    options.time_step = time_step;
    options.lambda = lambda;
    options.volume_lambda = volume_lambda;
    options.fix_boundary = fix_boundary;
    options.freeze_metric = freeze_metric;
    std::optional<py::error_already_set> interrupt;
    options.progress = [&](const FlowProgress&) {
        if (interrupt) {
            return false;
        }
        const py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) {
            interrupt = py::error_already_set();
        }
        return !interrupt;
    };
    FlowResult result;
    {
        const py::gil_scoped_release released;
        result = flow.run(mesh, options);
    }
    if (interrupt) {
        throw *interrupt;
    }
    if (!result.ok()) {
        throw SolverError("smooth: the flow failed after " + std::to_string(result.steps) +
                          " steps (" + to_string(result.status) + "): " + result.message);
    }
    py::dict info;
    info["status"] = to_string(result.status);
    info["steps"] = result.steps;
    info["seconds"] = result.seconds;
    info["energy"] = result.energy;
    return py::make_tuple(RowMatrixX3d(result.mesh.V), info);
}

}  // namespace

void bind_smoothing(py::module_& module) {
    module.def("smooth", &smooth, py::arg("V"), py::arg("F"), py::arg("method") = "volume-fairing",
               py::arg("steps") = 5, py::arg("time_step") = 0.5, py::arg("lambda_") = py::none(),
               py::arg("volume_lambda") = 0.05, py::arg("fix_boundary") = false,
               py::arg("freeze_metric") = false,
               "Smooths V by a gradient flow of the area: 'mcf' (explicit L2), 'fairing' (H1, "
               "implicit fairing), 'fairing2' (H2) or 'volume-fairing' (does not shrink). "
               "time_step and lambda_ in units of h² (h: the mean edge length). Returns the new "
               "V and a dict (status, steps, seconds, energy per step). freeze_metric: the "
               "input's metric at every step (fairing factors once). Ctrl-C stops it and "
               "raises KeyboardInterrupt.");
}

}  // namespace genflow::python
