// SPDX-License-Identifier: MIT
// The parts of the Python module genflow._core, each bound in its own file.
#pragma once

#include <pybind11/pybind11.h>

#include "genflow/mesh.h"

namespace genflow::python {

/// numpy's layout of vertices and faces: a row each.
using RowMatrixX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMatrixX3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// A mesh from numpy arrays V (#V×3, float) and F (#F×3, integer), copied into genflow's
/// column-major storage (one pass each: about a millisecond per 100K vertices).
TriangleMesh mesh_of(const Eigen::Ref<const RowMatrixX3d>& V,
                     const Eigen::Ref<const RowMatrixX3i>& F);

void bind_exceptions(pybind11::module_& module);
void bind_io(pybind11::module_& module);
void bind_operators(pybind11::module_& module);
void bind_smoothing(pybind11::module_& module);
void bind_distances(pybind11::module_& module);
void bind_match(pybind11::module_& module);

}  // namespace genflow::python
