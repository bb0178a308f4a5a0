// SPDX-License-Identifier: MIT
#include "matching/finest_bases.h"

#include "genflow/exceptions.h"
#include "genflow/matching/laplacian_commutativity.h"
#include "matching/analysis_store.h"
#include "matching/side_by_side.h"

namespace genflow::detail {

std::optional<FinestBases> finest_bases(const TriangleMesh& template_mesh,
                                        const TriangleMesh& target,
                                        const std::shared_ptr<TemplateCache>& template_cache) {
    constexpr int kCount = kCommutativityFunctions + 1;
    // The two bases are independent: each is found on a thread of its own.
    std::shared_ptr<const LaplacianEigenbasis> template_basis;
    std::optional<LaplacianEigenbasis> target_basis;
    try {
        run_side_by_side(2, [&](std::size_t k) {
            if (k == 0) {
                template_basis = cached<LaplacianEigenbasis>(
                    template_cache, "eigenbasis", template_mesh, kCount,
                    [&] { return laplacian_eigenbasis(template_mesh, kCount); });
            } else {
                target_basis = laplacian_eigenbasis(target, kCount);
            }
        });
    } catch (const SolverError&) {
        return std::nullopt;
    }
    return FinestBases{*template_basis, std::move(*target_basis)};
}

}  // namespace genflow::detail
