// SPDX-License-Identifier: MIT
// The discrete operators: the cotan stiffness matrix and the mass matrices (scipy.sparse).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "genflow/exceptions.h"
#include "genflow/operators/cotan_stiffness.h"
#include "genflow/operators/mass_matrix.h"
#include "genflow/operators/normals.h"

namespace py = pybind11;

namespace genflow::python {

namespace {

MassType mass_type(const std::string& name) {
    if (name == "full") {
        return MassType::Full;
    }
    if (name == "barycentric") {
        return MassType::Barycentric;
    }
    if (name == "voronoi") {
        return MassType::Voronoi;
    }
    throw InvalidInput("mass_matrix: type must be 'full', 'barycentric' or 'voronoi', got '" +
                       name + "'");
}

}  // namespace

void bind_operators(py::module_& module) {
    module.def(
        "cotan_stiffness",
        [](const Eigen::Ref<const RowMatrixX3d>& V, const Eigen::Ref<const RowMatrixX3i>& F) {
            return cotan_stiffness(mesh_of(V, F));
        },
        py::arg("V"), py::arg("F"),
        "The cotan stiffness matrix K (scipy.sparse, #V×#V): symmetric positive semi-definite, "
        "K·1 = 0, the FEM stiffness ∫∇φ_i·∇φ_j (the Laplace–Beltrami operator is −M⁻¹K).");
    module.def(
        "mass_matrix",
        [](const Eigen::Ref<const RowMatrixX3d>& V, const Eigen::Ref<const RowMatrixX3i>& F,
           const std::string& type) { return mass_matrix(mesh_of(V, F), mass_type(type)); },
        py::arg("V"), py::arg("F"), py::arg("type") = "voronoi",
        "The mass matrix (scipy.sparse, #V×#V) of type 'full', 'barycentric' or 'voronoi' "
        "(lumped, mixed Voronoi areas); its entries sum to the surface area.");
    module.def(
        "vertex_normals",
        [](const Eigen::Ref<const RowMatrixX3d>& V, const Eigen::Ref<const RowMatrixX3i>& F) {
            return RowMatrixX3d(vertex_normals(mesh_of(V, F)));
        },
        py::arg("V"), py::arg("F"), "Area-weighted unit vertex normals, #V×3.");
}

}  // namespace genflow::python
