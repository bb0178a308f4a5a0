// SPDX-License-Identifier: MIT
#include "genflow/energies/enclosed_volume_energy.h"

#include "genflow/operators/volume.h"

namespace genflow {

double EnclosedVolumeEnergy::value(const TriangleMesh& mesh) const {
    return enclosed_volume(mesh);
}

VertexField EnclosedVolumeEnergy::differential(const TriangleMesh& mesh) const {
    return enclosed_volume_gradient(mesh);
}

}  // namespace genflow
