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
        TwoAnalyses<LaplacianEigenbasis> bases = analysed_side_by_side<LaplacianEigenbasis>(
            template_cache, "eigenbasis", template_mesh, target, kCount,
            [](const TriangleMesh& mesh) { return laplacian_eigenbasis(mesh, kCount); });
        return FinestBases{*bases.of_template, std::move(bases.of_target)};
    } catch (const SolverError&) {
        return std::nullopt;
    }
}

}  // namespace genflow::detail
