// SPDX-License-Identifier: MIT
// genflow's exceptions as Python exceptions of the same names, each a subclass of the Python
// exception a caller would catch without knowing genflow: InvalidInput a ValueError, IoError
// an OSError (OutputError one of its kind), SolverError a RuntimeError.
#include "genflow/exceptions.h"

#include <pybind11/pybind11.h>

#include "bindings.h"

namespace genflow::python {

void bind_exceptions(pybind11::module_& module) {
    const auto& io_error = pybind11::register_exception<IoError>(module, "IoError", PyExc_OSError);
    // Registered after IoError: pybind11 tries the translators newest first, so an OutputError
    // is raised as such, not as the IoError it also is.
    pybind11::register_exception<OutputError>(module, "OutputError", io_error.ptr());
    pybind11::register_exception<InvalidInput>(module, "InvalidInput", PyExc_ValueError);
    pybind11::register_exception<SolverError>(module, "SolverError", PyExc_RuntimeError);
}

}  // namespace genflow::python
