// SPDX-License-Identifier: MIT
#include "genflow/energies/surface_area_energy.h"

#include "genflow/operators/area.h"
#include "operators/stiffness_pattern.h"

namespace genflow {

struct SurfaceAreaEnergy::PatternCache : detail::StiffnessPatternCache {};

SurfaceAreaEnergy::SurfaceAreaEnergy(CotanOptions options)
    : options_(options), pattern_cache_(std::make_unique<PatternCache>()) {}
SurfaceAreaEnergy::~SurfaceAreaEnergy() = default;
SurfaceAreaEnergy::SurfaceAreaEnergy(const SurfaceAreaEnergy& other)
    : SurfaceAreaEnergy(other.options_) {}
SurfaceAreaEnergy& SurfaceAreaEnergy::operator=(const SurfaceAreaEnergy& other) {
    if (this != &other) {
        options_ = other.options_;
        pattern_cache_ = std::make_unique<PatternCache>();
    }
    return *this;
}
SurfaceAreaEnergy::SurfaceAreaEnergy(SurfaceAreaEnergy&&) noexcept = default;
SurfaceAreaEnergy& SurfaceAreaEnergy::operator=(SurfaceAreaEnergy&&) noexcept = default;

double SurfaceAreaEnergy::value(const TriangleMesh& mesh) const {
    return surface_area(mesh);
}

VertexField SurfaceAreaEnergy::differential(const TriangleMesh& mesh) const {
    return surface_area_gradient(mesh);
}

std::optional<Linearization> SurfaceAreaEnergy::linearize(const TriangleMesh& mesh) const {
    // K to the bit (StiffnessPattern), written into the slots of the last connectivity instead
    // of sorting 12 triplets per face: on the 48K horse 4 instead of 14 ms, a tenth of a
    // volume-controlled fairing step.
    Eigen::SparseMatrix<double> K =
        pattern_cache_
            ? pattern_cache_->diagonal_plus_stiffness(mesh, Eigen::VectorXd::Zero(mesh.V.rows()),
                                                      1.0, options_, "SurfaceAreaEnergy::linearize")
            : cotan_stiffness(mesh, options_);  // !pattern_cache_: moved from
    return Linearization{std::move(K), VertexField::Zero(mesh.V.rows(), 3)};
}

}  // namespace genflow
