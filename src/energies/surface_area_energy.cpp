// SPDX-License-Identifier: MIT
#include "genflow/energies/surface_area_energy.h"

#include "genflow/operators/area.h"

namespace genflow {

double SurfaceAreaEnergy::value(const TriangleMesh& mesh) const {
    return surface_area(mesh);
}

VertexField SurfaceAreaEnergy::differential(const TriangleMesh& mesh) const {
    return surface_area_gradient(mesh);
}

std::optional<Linearization> SurfaceAreaEnergy::linearize(const TriangleMesh& mesh) const {
    return Linearization{cotan_stiffness(mesh, options_), VertexField::Zero(mesh.V.rows(), 3)};
}

}  // namespace genflow
