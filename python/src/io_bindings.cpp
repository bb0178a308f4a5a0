// SPDX-License-Identifier: MIT
// Reading, writing and validating meshes: V and F as numpy arrays, attributes as a dict.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "genflow/io/read_mesh.h"
#include "genflow/io/write_mesh.h"
#include "genflow/mesh/validate.h"

namespace py = pybind11;

namespace genflow::python {

namespace {

// What a file gave beside positions and faces, as a dict of arrays (only what it gave).
py::dict attributes_dict(VertexAttributes attributes) {
    py::dict out;
    if (attributes.colors.rows() > 0) {
        out["colors"] = py::cast(std::move(attributes.colors));
    }
    if (attributes.normals.rows() > 0) {
        out["normals"] = py::cast(RowMatrixX3d(attributes.normals));
    }
    if (attributes.uvs.rows() > 0) {
        out["uvs"] =
            py::cast(Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>(attributes.uvs));
    }
    py::dict values;
    for (auto& [name, field] : attributes.scalars) {
        values[py::str(name)] = py::cast(std::move(field));
    }
    if (!values.empty()) {
        out["values"] = values;
    }
    return out;
}

// The dict's arrays as VertexAttributes ("colors" uint8 #V×3, "normals" #V×3, "uvs" #V×2,
// "values" {name: #V}).
VertexAttributes attributes_of(const py::dict& given) {
    VertexAttributes attributes;
    if (given.contains("colors")) {
        attributes.colors = given["colors"].cast<VertexColors>();
    }
    if (given.contains("normals")) {
        attributes.normals = given["normals"].cast<RowMatrixX3d>();
    }
    if (given.contains("uvs")) {
        attributes.uvs =
            given["uvs"].cast<Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>>();
    }
    if (given.contains("values")) {
        for (const auto& [name, field] : given["values"].cast<py::dict>()) {
            attributes.scalars.emplace_back(name.cast<std::string>(),
                                            field.cast<Eigen::VectorXd>());
        }
    }
    return attributes;
}

py::tuple read(const std::filesystem::path& path, bool with_attributes) {
    std::vector<std::string> warnings;
    VertexAttributes attributes;
    TriangleMesh mesh = read_mesh(path, &warnings, with_attributes ? &attributes : nullptr);
    RowMatrixX3d V = mesh.V;
    RowMatrixX3i F = mesh.F;
    if (!with_attributes) {
        return py::make_tuple(std::move(V), std::move(F));
    }
    return py::make_tuple(std::move(V), std::move(F), attributes_dict(std::move(attributes)));
}

py::dict validation_dict(const ValidationReport& report) {
    py::dict out;
    out["ok"] = report.ok();
    out["closed"] = report.closed();
    out["vertices"] = report.num_vertices;
    out["faces"] = report.num_faces;
    out["edges"] = report.num_edges;
    out["components"] = report.components;
    out["boundary_loops"] = report.boundary_loops;
    out["genus"] = report.genus ? py::cast(*report.genus) : py::none();
    py::list issues;
    for (const ValidationIssue& issue : report.issues) {
        issues.append(
            py::make_tuple(issue.severity == Severity::Error ? "error" : "warning", issue.message));
    }
    out["issues"] = issues;
    return out;
}

}  // namespace

void bind_io(py::module_& module) {
    module.def("read_mesh", &read, py::arg("path"), py::arg("attributes") = false,
               "V (#V×3 float64), F (#F×3 int32) of an OBJ, PLY, OFF or STL file; with "
               "attributes=True also a dict of what the file gives beside them (colors, normals, "
               "uvs, values).");
    module.def(
        "write_mesh",
        [](const std::filesystem::path& path, const Eigen::Ref<const RowMatrixX3d>& V,
           const Eigen::Ref<const RowMatrixX3i>& F, const py::dict& attributes) {
            std::vector<std::string> warnings;
            write_mesh(path, mesh_of(V, F), attributes_of(attributes), {}, &warnings);
            return warnings;
        },
        py::arg("path"), py::arg("V"), py::arg("F"), py::arg("attributes") = py::dict(),
        "Writes V, F (and attributes, as read_mesh gives them) atomically as OBJ, PLY, OFF, STL "
        "or glTF (.glb) by the extension; returns the warnings (what the format cannot hold).");
    module.def(
        "validate",
        [](const Eigen::Ref<const RowMatrixX3d>& V, const Eigen::Ref<const RowMatrixX3i>& F) {
            return validation_dict(validate(mesh_of(V, F)));
        },
        py::arg("V"), py::arg("F"),
        "The mesh's validation report as a dict: ok, closed, counts, genus and the issues as "
        "(severity, message) pairs.");
}

}  // namespace genflow::python
