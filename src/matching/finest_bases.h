// SPDX-License-Identifier: MIT
// The finest template's and target's lowest Laplacian eigenpairs, computed once per match for
// the stages that read the whole match intrinsically: the judge of the readings
// (signatures_reading.h) and the counterparts (counterparts.h).
#pragma once

#include <memory>
#include <optional>

#include "genflow/matching/template_cache.h"
#include "genflow/mesh.h"
#include "genflow/operators/laplacian_eigenbasis.h"

namespace genflow::detail {

struct FinestBases {
    LaplacianEigenbasis template_basis;
    LaplacianEigenbasis target_basis;
};

/// The kCommutativityFunctions + 1 lowest eigenpairs of each surface (40 non-constant
/// functions resolve regions of about a fortieth of the surface: a hand, a foot, a side of the
/// head), or nothing if the Lanczos iterations do not converge. The template's is kept in
/// `template_cache`, where there is one.
[[nodiscard]] std::optional<FinestBases> finest_bases(
    const TriangleMesh& template_mesh, const TriangleMesh& target,
    const std::shared_ptr<TemplateCache>& template_cache = {});

}  // namespace genflow::detail
