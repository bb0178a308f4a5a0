// SPDX-License-Identifier: MIT
// The signatures' reading (MatchOptions::signatures_reading): the match made a second time with
// the eigenfunctions off, its coarsest last round guided by the heat kernel signatures alone.
// The eigenfunctions tell left from right and pay on most pairs, but they are only as right as
// the first round's map that carried them: where it was wrong they hold the template in a
// wrong place that d_H and the disagreement cannot see (docs/matching.md, "The signatures'
// reading"). Of the two readings, the one whose map commutes better with the surfaces'
// Laplacians is kept (keeps_signatures_reading(), selection.h).
#pragma once

#include <Eigen/Core>
#include <optional>

#include "genflow/matching/match.h"
#include "genflow/matching/spectral_map.h"
#include "genflow/mesh.h"
#include "matching/finest_bases.h"
#include "matching/selection.h"

namespace genflow::detail {

/// Whether a match with `options` reads a second time with the signatures: the stage is on and
/// the first reading is guided by the eigenfunctions.
[[nodiscard]] bool reads_with_signatures(const MatchOptions& options);

/// The options of the second reading: `options` with the eigenfunctions off.
[[nodiscard]] MatchOptions signatures_reading_options(const MatchOptions& options);

/// The judge of the readings: the commutativity (laplacian_commutativity()) of the map each
/// deformed template implies, in the finest template's and target's eigenbases; where asked,
/// also whether that map keeps the surface's orientation (MapOrientation), which the match
/// reports and does not judge by.
class ReadingJudge {
public:
    /// Keeps `bases` and `target` by reference. With `orientation`, the orientation's spectra
    /// are computed here.
    ReadingJudge(const FinestBases& bases, const TriangleMesh& template_mesh,
                 const TriangleMesh& target, bool orientation);

    /// The score of the map that puts each template vertex on the target's closest point to
    /// where `deformed` puts it (for the orientation, on that point's nearest corner).
    [[nodiscard]] ReadingScore score(const Eigen::MatrixX3d& deformed) const;

private:
    const FinestBases& bases_;
    const TriangleMesh& target_;
    std::optional<MapOrientation> orientation_;
};

}  // namespace genflow::detail
