// SPDX-License-Identifier: MIT
// genflow._core: the library for Python, arrays as numpy arrays. The package genflow
// (python/genflow/__init__.py) re-exports it.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "genflow/threads.h"
#include "genflow/version.h"

namespace genflow::python {

TriangleMesh mesh_of(const Eigen::Ref<const RowMatrixX3d>& V,
                     const Eigen::Ref<const RowMatrixX3i>& F) {
    return TriangleMesh{V, F};
}

}  // namespace genflow::python

PYBIND11_MODULE(_core, module) {
    module.doc() = "genflow: generalized gradient flows of triangle meshes";
    module.attr("__version__") = std::string(genflow::kVersion);
    genflow::python::bind_exceptions(module);
    genflow::python::bind_io(module);
    genflow::python::bind_operators(module);
    genflow::python::bind_smoothing(module);
    genflow::python::bind_distances(module);
    genflow::python::bind_match(module);
    module.def("set_thread_count", &genflow::set_thread_count, pybind11::arg("count"),
               "Threads of genflow's parallel sums from now on (results do not depend on it).");
    module.def("thread_count", &genflow::thread_count,
               "The number of threads genflow's parallel sums use.");
}
