// SPDX-License-Identifier: MIT
// Exact surface distances and the pseudo-Hausdorff distance with its gradient.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "genflow/energies/pseudo_hausdorff_energy.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/spatial/surface_distance.h"

namespace py = pybind11;

namespace genflow::python {

namespace {

using Vertices = Eigen::Ref<const RowMatrixX3d>;
using Faces = Eigen::Ref<const RowMatrixX3i>;

py::dict one_sided(const OneSidedDistance& d, bool mean_and_rms) {
    py::dict out;
    out["hausdorff"] = d.hausdorff;
    out["hausdorff_upper_bound"] = d.hausdorff_upper_bound;
    if (mean_and_rms) {
        out["mean"] = d.mean;
        out["rms"] = d.rms;
    }
    return out;
}

py::dict distances(const Vertices& VA, const Faces& FA, const Vertices& VB, const Faces& FB,
                   bool mean_and_rms) {
    const TriangleMesh a = mesh_of(VA, FA);
    const TriangleMesh b = mesh_of(VB, FB);
    SurfaceDistances d;
    {
        const py::gil_scoped_release released;
        d = surface_distances(a, b, {.mean_and_rms = mean_and_rms});
    }
    py::dict out;
    out["hausdorff"] = d.hausdorff;
    out["hausdorff_upper_bound"] = d.hausdorff_upper_bound;
    if (mean_and_rms) {
        out["mean"] = d.mean;
        out["rms"] = d.rms;
    }
    out["a_to_b"] = one_sided(d.a_to_b, mean_and_rms);
    out["b_to_a"] = one_sided(d.b_to_a, mean_and_rms);
    return out;
}

// d_H of the moving mesh (V, F) to the target and its gradient with respect to V.
py::tuple pseudo_hausdorff_of(const Vertices& V, const Faces& F, const Vertices& VT,
                              const Faces& FT, double alpha, double epsilon) {
    const TriangleMesh moving = mesh_of(V, F);
    const TriangleMesh target = mesh_of(VT, FT);
    PseudoHausdorffOptions options;
    options.alpha = alpha;
    options.epsilon = epsilon > 0 ? epsilon : mean_edge_length(target);
    double value = 0;
    RowMatrixX3d gradient;
    {
        const py::gil_scoped_release released;
        const PseudoHausdorffEnergy energy(target, options);
        const PseudoHausdorffEvaluation evaluation = energy.evaluate(moving);
        value = evaluation.value;
        gradient = evaluation.differential;
    }
    return py::make_tuple(value, std::move(gradient));
}

}  // namespace

void bind_distances(py::module_& module) {
    module.def("surface_distances", &distances, py::arg("VA"), py::arg("FA"), py::arg("VB"),
               py::arg("FB"), py::kw_only(), py::arg("mean_and_rms") = true,
               "Exact distances between the surfaces A and B: hausdorff (with a proven upper "
               "bound), mean, rms, and each one-sided (a_to_b, b_to_a), as a dict. "
               "mean_and_rms=False: the Hausdorff distances alone, much faster.");
    module.def("pseudo_hausdorff", &pseudo_hausdorff_of, py::arg("V"), py::arg("F"),
               py::arg("V_target"), py::arg("F_target"), py::arg("alpha") = 8.0,
               py::arg("epsilon") = 0.0,
               "The paper's differentiable pseudo-Hausdorff distance d_H of the mesh (V, F) to "
               "the target, and its gradient with respect to V (#V×3, the vertex masses held "
               "fixed). epsilon 0: the target's mean edge length.");
}

}  // namespace genflow::python
