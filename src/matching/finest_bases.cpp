// SPDX-License-Identifier: MIT
#include "matching/finest_bases.h"

#include "genflow/exceptions.h"
#include "genflow/matching/laplacian_commutativity.h"
#include "matching/analysis_store.h"

namespace genflow::detail {

std::optional<FinestBases> finest_bases(const TriangleMesh& template_mesh,
                                        const TriangleMesh& target,
                                        const std::shared_ptr<TemplateCache>& template_cache) {
    constexpr int kCount = kCommutativityFunctions + 1;
    try {
        return FinestBases{*cached<LaplacianEigenbasis>(
                               template_cache, "eigenbasis", template_mesh, kCount,
                               [&] { return laplacian_eigenbasis(template_mesh, kCount); }),
                           laplacian_eigenbasis(target, kCount)};
    } catch (const SolverError&) {
        return std::nullopt;
    }
}

}  // namespace genflow::detail
