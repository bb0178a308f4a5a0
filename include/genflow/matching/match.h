// SPDX-License-Identifier: MIT
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "genflow/flows/flow.h"
#include "genflow/matching/rigid_alignment.h"
#include "genflow/mesh.h"
#include "genflow/metrics/subspace_metric.h"

namespace genflow {

/// The deformation prior of a match: the metric in which the template flows (paper §6.3).
enum class MatchPrior {
    L2,     ///< plain L2: the baseline that slides and tears (paper Fig. 3)
    H1,     ///< Sobolev H1: smooth, but no notion of rigidity
    Rigid,  ///< quasi-rigid (paper eq. 16, SPEC.md §5): rigid motion and scaling are cheap
};

/// "l2", "h1", "rigid".
[[nodiscard]] const char* to_string(MatchPrior prior);
/// The prior named by `name` (as to_string() spells it), or nothing.
[[nodiscard]] std::optional<MatchPrior> parse_match_prior(const std::string& name);

/// What the progress callback sees after every accepted step.
struct MatchProgress {
    std::string stage;  ///< "align", or the prior's name while flowing
    int step = 0;
    int max_steps = 0;
    double energy = 0;                   ///< d_H after this step
    const TriangleMesh* mesh = nullptr;  ///< the deformed template (valid during the call)
};

/// Parameters of match(). Every length is relative to the meshes, so the defaults need no
/// tuning per pair (issue 5: scale-free parameters).
struct MatchOptions {
    MatchPrior prior = MatchPrior::Rigid;
    /// Exponent α of the pseudo-Hausdorff distance and its truncation τ (PseudoHausdorffOptions);
    /// ε is the target's mean edge length (SPEC.md §8: smaller makes vertices snap
    /// tangentially).
    double alpha = 8;
    double truncation = 1e-4;
    /// At most this many steps of the flow.
    int max_iterations = 300;
    /// No vertex moves farther than this fraction of the target's bounding-box diagonal in one
    /// step (SPEC.md §9: 2 %).
    double max_step = 0.02;
    /// Converged when d_H fell by less than this fraction over the last 20 steps.
    double stagnation_tolerance = 1e-4;
    /// Start from a global rigid alignment (so inputs need no pre-alignment); with several
    /// distinct rigid optima, the best `alignment_candidates` are each flowed and the lowest
    /// final d_H wins.
    bool align = true;
    int alignment_candidates = 1;
    RigidAlignmentOptions alignment;
    /// Penalties of the quasi-rigid prior.
    QuasiRigidOptions rigid;
    /// H1 smoothing length as a multiple of the template's mean edge length: λ = (k·h)².
    double h1_length = 5;
    /// Called after every step; return false to stop. Optional.
    std::function<bool(const MatchProgress&)> progress = {};
};

/// What match() did, for the report.
struct MatchResult {
    TriangleMesh deformed;          ///< the template, deformed (its connectivity unchanged)
    Similarity initial_alignment;   ///< the rigid start (identity without `align`)
    int iterations = 0;             ///< flow steps
    FlowStatus status = FlowStatus::MaxSteps;
    double hausdorff_energy = 0;    ///< final d_H
    std::vector<double> energy;     ///< d_H after alignment and after every step
    double alignment_seconds = 0;
    double flow_seconds = 0;
    /// True if the flow stopped on its own (stagnation or no descent left), not on a limit.
    [[nodiscard]] bool converged() const { return status == FlowStatus::Converged; }
};

/// Deforms `template_mesh` onto `target` (another pose of the same subject, any sampling and
/// connectivity) by the flow of the pseudo-Hausdorff distance in the metric of the prior
/// (paper eq. 14): optional global rigid alignment (align_rigidly()), then steepest descent
/// with Armijo backtracking and a displacement cap (gradient_descent()).
///
/// \throws InvalidInput if a mesh is empty, has no face, zero area, bad indices or non-finite
///         coordinates, or an option is out of range.
[[nodiscard]] MatchResult match(const TriangleMesh& template_mesh, const TriangleMesh& target,
                                const MatchOptions& options = {});

}  // namespace genflow
