// SPDX-License-Identifier: MIT
#include "matching/finest_bases.h"

#include "genflow/exceptions.h"
#include "genflow/matching/laplacian_commutativity.h"

namespace genflow::detail {

std::optional<FinestBases> finest_bases(const TriangleMesh& template_mesh,
                                        const TriangleMesh& target) {
    try {
        return FinestBases{laplacian_eigenbasis(template_mesh, kCommutativityFunctions + 1),
                           laplacian_eigenbasis(target, kCommutativityFunctions + 1)};
    } catch (const SolverError&) {
        return std::nullopt;
    }
}

}  // namespace genflow::detail
