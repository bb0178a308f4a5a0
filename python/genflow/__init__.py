# SPDX-License-Identifier: MIT
"""genflow: generalized gradient flows of triangle meshes.

Meshes are numpy arrays: V (#V x 3, float64) and F (#F x 3, int32). Errors are raised as
genflow.InvalidInput (a ValueError), genflow.IoError (an OSError; OutputError one of its kind)
and genflow.SolverError (a RuntimeError).
"""

from ._core import (
    InvalidInput,
    IoError,
    OutputError,
    PartModel,
    SolverError,
    TemplateCache,
    __version__,
    cotan_stiffness,
    mass_matrix,
    match,
    pseudo_hausdorff,
    read_mesh,
    read_part_model,
    set_thread_count,
    smooth,
    surface_distances,
    thread_count,
    validate,
    vertex_normals,
    write_mesh,
)

__all__ = [
    "InvalidInput",
    "IoError",
    "OutputError",
    "PartModel",
    "SolverError",
    "TemplateCache",
    "__version__",
    "cotan_stiffness",
    "mass_matrix",
    "match",
    "pseudo_hausdorff",
    "read_mesh",
    "read_part_model",
    "set_thread_count",
    "smooth",
    "surface_distances",
    "thread_count",
    "validate",
    "vertex_normals",
    "write_mesh",
]
