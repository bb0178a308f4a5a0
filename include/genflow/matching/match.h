// SPDX-License-Identifier: MIT
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "genflow/flows/flow.h"
#include "genflow/flows/gradient_descent.h"
#include "genflow/matching/landmarks.h"
#include "genflow/matching/partial_target.h"
#include "genflow/matching/rigid_alignment.h"
#include "genflow/matching/template_cache.h"
#include "genflow/mesh.h"
#include "genflow/metrics/quasi_isometric_metric.h"
#include "genflow/metrics/subspace_metric.h"
#include "genflow/parts/quasi_articulated_metric.h"

namespace genflow {

/// The deformation prior of a match: the metric in which the template flows (paper §6.3).
enum class MatchPrior {
    L2,     ///< plain L2: the baseline that slides and tears (paper Fig. 3)
    H1,     ///< Sobolev H1: smooth, but no notion of rigidity
    Rigid,  ///< quasi-rigid (paper eq. 16, docs/formulas.md §5): rigid motion and scaling are cheap
    Articulated,  ///< quasi-articulated (docs/formulas.md §6): needs MatchOptions::parts
    Isometric,  ///< quasi-isometric (docs/formulas.md §7): bends freely, resists local stretching
};

/// Every prior, in declaration order.
inline constexpr std::array<MatchPrior, 5> kMatchPriors{MatchPrior::L2, MatchPrior::H1,
                                                        MatchPrior::Rigid, MatchPrior::Articulated,
                                                        MatchPrior::Isometric};

/// "l2", "h1", "rigid", "articulated", "isometric".
[[nodiscard]] const char* to_string(MatchPrior prior);
/// The names of kMatchPriors (for command-line choices).
[[nodiscard]] std::vector<std::string> match_prior_names();
/// The prior named by `name` (as to_string() spells it), or nothing.
[[nodiscard]] std::optional<MatchPrior> parse_match_prior(const std::string& name);

/// What the progress callback sees after every accepted step.
struct MatchProgress {
    int level = 0;  ///< 0 is the finest; levels − 1 the coarsest
    int levels = 1;
    int step = 0;
    int max_steps = 0;
    double energy = 0;                   ///< d_H after this step
    const TriangleMesh* mesh = nullptr;  ///< the deformed template (valid during the call)
    /// Per vertex of `mesh`, the template's vertex it is (the levels are nested): a vertex of
    /// the template as repair_surface() makes it, which is the input itself unless it needed a
    /// repair (MatchResult::template_repairs).
    const std::vector<Eigen::Index>* template_vertex = nullptr;
};

/// A level's deformed template after one stage of match()'s work, for diagnostics
/// (MatchOptions::stages): compared with a ground truth, it tells which stage lost accuracy.
struct MatchStage {
    int level = 0;  ///< 0 is the finest; levels − 1 the coarsest
    int levels = 1;
    /// "coarsest": the coarsest level's kept result (after the start selection, the guided
    /// rounds, the second opinion and the limb exchanges); then per finer level "carried" (the
    /// coarser result transferred, before any flow), "flowed" (after the level's flows) and
    /// "done" (the level's result, after turning parts back, fits to the fine map and limb
    /// exchanges, where the level has them).
    std::string_view stage;
    const TriangleMesh* mesh = nullptr;  ///< the deformed template (valid during the call)
    /// Per vertex of `mesh`, the input template's vertex it is (the levels are nested).
    const std::vector<Eigen::Index>* template_vertex = nullptr;
};

/// Above this intrinsic disagreement (MatchResult::intrinsic_disagreement) a match is doubtful:
/// above what right matches measure (up to 0.31), below what a match with an arm on a leg did
/// (0.39; docs/measurements.md, "Doubtful matches").
inline constexpr double kDoubtfulDisagreement = 0.35;

/// The coarsest level's rigid starts (src/matching/coarsest_level.h): alignment hypotheses,
/// each flowed briefly in the H1 metric and judged by how far it disagrees with the target
/// intrinsically.
struct StartOptions {
    /// Start from rigid alignments; off: from the inputs' frames, as placed.
    bool enabled = true;
    /// Rigid starts flowed, `selection_iterations` H1 steps each.
    int candidates = 6;
    int selection_iterations = 300;
    /// The shortlist: the starts whose d_H ends within this share of the lowest.
    double selection_tolerance = 0.05;
    /// Options of the rigid alignment.
    RigidAlignmentOptions alignment;
};

/// The coarsest level's guided rounds (src/matching/guided_rounds.h), in h1, articulated and
/// isometric matches: d_H augmented with descriptors, so that a point is near only to points
/// both close and alike.
struct GuidedRoundOptions {
    bool enabled = true;
    /// Weight of the heat kernel signatures in the first round, as a fraction of the target's
    /// diagonal per standard deviation (0 = no guided rounds).
    double signature_guidance = 0.1;
    /// Weight of the eigenfunctions, carried over by the functional map the first round implies,
    /// in the last round and the refinement: they tell left from right (0 = the last round
    /// guided by the signatures).
    double eigenfunction_guidance = 0.1;
    /// The last round also at eigenfunction_guidance × 2^j, j < this; the least disagreeing
    /// result is kept.
    int guidance_candidates = 1;
    /// Weight of the template's edge stretching (times the diagonal) in the last round: d_H
    /// cannot see tangential sliding (0 = none).
    double stretch_weight = 0.1;
    /// The last round at stretch_weight × 4^k, k < this, the stiffer ones settled at
    /// stretch_weight; the least disagreeing result is kept.
    int stiffness_candidates = 3;
    /// A doubtful last round runs again guided by the signatures alone, kept if it disagrees
    /// less.
    bool signature_fallback = true;
};

/// The second opinion (src/matching/intrinsic_start.h): the guided rounds also from an
/// intrinsic start (the extremities matched by geodesic distances), kept by
/// detail::replaces().
struct SecondOpinionOptions {
    bool enabled = true;
    /// 0: asked of every match, side by side with the rigid starts; above 0, only of results
    /// that disagree more than this, after them.
    double above = 0;
    /// A result that disagrees more than `alternative_starts_above`, whichever start it came
    /// from, is matched again from the intrinsic starts of up to this many further landmark
    /// sets; the least disagreeing is kept (0 = none).
    int alternative_starts = 3;
    /// Below it a result stands: right matches disagree this little (0 = every result).
    double alternative_starts_above = 0.15;
};

/// The exchange of limbs the match put on each other's places (src/matching/swapped_limbs.h),
/// at the coarsest and the second coarsest level, kept by detail::keeps_limb_exchange(). Needs
/// the second opinion's analyses.
struct LimbSwapOptions {
    bool enabled = true;
};

/// The second coarsest level's guided refinement (src/matching/finer_levels.h): flows guided by
/// the eigenfunctions at eigenfunction_guidance × 2^-j, j < `guidances`, before the plain
/// flow; of those and the plain flow alone, the least disagreeing is kept.
struct RefinementOptions {
    bool enabled = true;
    int guidances = 2;
};

/// Turning back the parts of the second coarsest level that a fine functional map places
/// turned over (more than 90°, not a reflection), kept if d_H stays about as low.
struct TurnBackOptions {
    bool enabled = true;
};

/// Fits of the second coarsest level to where a fine functional map puts it, each kept only by
/// detail::first_kept_fit().
struct MapFitOptions {
    bool enabled = true;
    int max_fits = 6;
};

/// The signatures' reading (src/matching/signatures_reading.h): the match made again with the
/// eigenfunctions off (MatchOptions::guided.eigenfunction_guidance = 0); of the two, the one
/// whose map commutes better with the surfaces' Laplacians (laplacian_commutativity()) is kept.
/// The eigenfunctions are only as right as the map that carried them.
struct SignaturesReadingOptions {
    bool enabled = true;
    /// Also report each reading's orientation_ratio() (MatchResult::first_orientation): a
    /// diagnosis, not a rule, so off by default, as it costs two eigen-solves of the whole
    /// meshes (docs/matching.md, "The signatures' reading").
    bool report_orientation = false;
};

/// Each template vertex's counterpart on the target (src/matching/counterparts.h,
/// MatchResult::counterparts): among the target's points near where the match put the vertex,
/// the one the Laplacian eigenfunctions agree with, instead of the closest point, which lands on
/// the wrong one of two parts that touch. The deformed template does not change (docs/matching.md,
/// "Counterparts").
struct CounterpartOptions {
    bool enabled = true;
    /// How far, over the target's √area, a counterpart may be from where the match put the
    /// vertex: a move this long costs as much as the eigenfunctions' mismatch between two
    /// unrelated points. A few fingers' widths on a body, more than a match is off where right.
    double reach = 0.05;
};

/// Parameters of match(). Every length is relative to the meshes, so the defaults need no
/// tuning per pair. Each stage of the pipeline has its options and an `enabled` switch; what each
/// was measured to do: docs/matching.md, "Options".
struct MatchOptions {
    /// The deformation prior: the metric of the flow.
    MatchPrior prior = MatchPrior::H1;
    /// Exponent α of d_H (docs/formulas.md §8).
    double alpha = 8;
    /// Truncation τ of d_H's sums: their relative error stays below τ/(2α).
    double truncation = 1e-2;
    /// Resolution levels (paper §6.4); 0 chooses them: the coarsest about `coarse_vertices`, each
    /// finer 4× more.
    int levels = 0;
    Eigen::Index coarse_vertices = 1000;
    /// The first half of the coarsest level flows with ε this many times larger (a smoother d_H); 1
    /// = off.
    double coarse_epsilon = 1;
    /// At most this many steps per flow on the coarsest level, and per flow on each finer one.
    int max_iterations = 300;
    int fine_iterations = 15;
    /// No vertex moves farther than this fraction of the target's diagonal in one step.
    double max_step = 0.02;
    /// Implicit steps (paper eq. 11) instead of explicit ones: faster, not better.
    bool implicit = false;
    /// Quasi-Newton steps (DescentOptions::quasi_newton_memory): L-BFGS in the prior's metric
    /// with this many past steps; 0, the steepest descent of eq. 14. Not with `implicit`.
    int quasi_newton_memory = 0;
    /// Where each steepest flow step's backtracking starts (DescentOptions::first_step).
    /// LastDecrease takes about one d_H evaluation a step where Doubling takes 1.5; why it is
    /// not the default: docs/matching.md, "first_step".
    FirstStep first_step = FirstStep::Doubling;
    /// A flow has converged when d_H fell by less than this fraction over its last 20 steps.
    double stagnation_tolerance = 1e-3;
    /// Steps of each further flow on the second coarsest level (its guided refinement, the
    /// turn-back and the fits to the fine map).
    int refinement_iterations = 50;
    StartOptions starts;
    GuidedRoundOptions guided;
    SecondOpinionOptions second_opinion;
    LimbSwapOptions limb_swaps;
    RefinementOptions refinement;
    TurnBackOptions turn_back;
    MapFitOptions map_fit;
    SignaturesReadingOptions signatures_reading;
    CounterpartOptions counterparts;
    /// Template vertices whose places on the target the user knows (none by default).
    LandmarkOptions landmarks;
    /// Whether the target shows all of the template or part of it, and how a part is matched.
    PartialTargetOptions partial;
    /// Penalties of the quasi-rigid prior.
    QuasiRigidOptions rigid;
    /// The template's parts (required by the articulated prior; joint centres in the template's own
    /// frame), and the prior's penalties.
    std::optional<PartModel> parts;
    QuasiArticulatedOptions articulated;
    /// The articulated prior's penalty of the global rigid motion on the finest level, in (0, 1],
    /// in place of `articulated.global`: boosted there, the finest level's short flow moved the
    /// whole template back and forth.
    double articulated_finest_global = 1;
    /// Parameters of the quasi-isometric prior (its metric is rebuilt every 4th step: about twice
    /// as fast, errors unchanged).
    QuasiIsometricOptions isometric{.refresh_interval = 4};
    /// H1 smoothing length as a multiple of the template's mean edge length: λ = (k·h)².
    double h1_length = 5;
    /// Called after every step; return false to stop. Optional. Where a level runs independent
    /// flows side by side (the rigid starts, the stiffness candidates, the refining flows), one of
    /// them reports, possibly from another thread than the caller's, and the others stop when
    /// it is told to: the callback is never called twice at once.
    std::function<bool(const MatchProgress&)> progress = {};
    /// Called with each level's result after each stage (MatchStage), from the calling thread;
    /// the signatures' reading's stages follow the first reading's. Optional; it does not change
    /// the match.
    std::function<void(const MatchStage&)> stages = {};
    /// The template's analyses from earlier matches of the same template (TemplateCache), found
    /// there instead of computed again, and this match's kept there; none: match() keeps them
    /// for itself alone. The result is the same either way.
    std::shared_ptr<TemplateCache> template_cache = {};
};

/// One level of a match, coarsest first in MatchResult::levels.
struct MatchLevel {
    Eigen::Index template_vertices = 0;
    Eigen::Index target_vertices = 0;
    /// Steps of all the level's flows (a guided coarsest level has several, a refined second
    /// coarsest level one plain and two per refining guidance).
    int iterations = 0;
    FlowStatus status = FlowStatus::MaxSteps;
    /// d_H at the start and the end of the level's flow (with the landmarks' term, where the
    /// match has landmarks: the energy the flow lowered).
    double energy_start = 0;
    double energy_end = 0;
    double seconds = 0;  ///< pyramid, transfer and flow of this level
    /// d_H (likewise) after each step of the flow whose result the level keeps, its start
    /// first: energy_start … energy_end.
    std::vector<double> energy;
};

/// The time one stage of match() took (MatchResult::stage_times).
struct MatchStageTime {
    std::string stage;   ///< its name, as MatchResult::stage_times lists them
    double seconds = 0;  ///< wall time
    /// The process's processor time over the stage, all its threads: what the stage costs
    /// whatever else waits for the machine's cores (other work of the same process counts too).
    double processor_seconds = 0;
};

/// What match() did, for the report.
struct MatchResult {
    TriangleMesh deformed;  ///< the template, deformed (its connectivity unchanged)
    /// Per template vertex, its counterpart: a point of the target's surface, where
    /// MatchOptions::counterparts put it, else the closest point to where `deformed` puts the
    /// vertex (match_correspondence() gives them as surface points).
    Eigen::MatrixX3d counterparts;
    /// How many template vertices MatchOptions::counterparts gave another target vertex than the
    /// one nearest to their closest point; nothing where the stage did not run.
    std::optional<Eigen::Index> counterparts_moved;
    Similarity initial_alignment;    ///< the rigid start (identity without `align`)
    std::vector<MatchLevel> levels;  ///< coarsest first
    double hausdorff_energy = 0;     ///< final d_H on the finest level (as MatchLevel's)
    /// Whether the target was matched as showing only part of the template
    /// (MatchOptions::partial: given, or found by shows_part_only()).
    bool partial_target = false;
    /// The landmarks' root-mean-square distance from their points at the end, over the target's
    /// diagonal; nothing without landmarks.
    std::optional<double> landmark_distance;
    /// The stretch weight of the kept last guided round
    /// (MatchOptions::guided.stiffness_candidates); 0 when no guided round had the stretching
    /// energy.
    double stretch_weight = 0;
    /// The eigenfunction guidance of the kept last round
    /// (MatchOptions::guided.guidance_candidates); 0 without it.
    double eigenfunction_guidance = 0;
    /// Whether the kept last round was guided by the signatures alone
    /// (MatchOptions::guided.signature_fallback); its eigenfunction_guidance is then 0.
    bool signature_fallback = false;
    /// The eigenfunction guidance of the kept refining flow of the second coarsest level
    /// (MatchOptions::refinement); 0 when its plain flow was kept or none ran.
    double refinement_guidance = 0;
    /// How many parts MatchOptions::turn_back turned back.
    int turned_parts = 0;
    /// How many fits to the fine map were kept (MatchOptions::map_fit).
    int map_fits = 0;
    /// The intrinsic disagreement of the second opinion (MatchOptions::second_opinion),
    /// if one was given, and whether its result was kept.
    std::optional<double> second_opinion_disagreement;
    bool second_opinion = false;
    /// How many intrinsic starts of further landmark sets were tried
    /// (MatchOptions::second_opinion.alternative_starts), and which was kept (its rank, 1 = the
    /// first after the second opinion's; 0 = none).
    int alternative_starts = 0;
    int alternative_start = 0;
    /// How many pairs of limbs MatchOptions::limb_swaps exchanged, at the coarsest and the
    /// refined level (0 if no match from the exchanges was kept, or none was tried). The other
    /// fields say where the coarsest result it started from came from.
    int swapped_limbs = 0;
    /// Whether the signatures' reading was kept (MatchOptions::signatures_reading), and the
    /// commutativity of each reading's map (laplacian_commutativity()) and its orientation
    /// (orientation_ratio(): above 1 it reverses it), where the reading ran (the orientation with
    /// SignaturesReadingOptions::report_orientation).
    bool signatures_reading = false;
    std::optional<double> first_commutativity;
    std::optional<double> signatures_commutativity;
    std::optional<double> first_orientation;
    std::optional<double> signatures_orientation;
    /// Where both readings ran, the template's vertices as the reading not kept deformed them
    /// (in `deformed`'s order): to look at beside the kept one, or to judge the judge.
    std::optional<Eigen::MatrixX3d> other_reading;
    /// How far the coarsest level's result disagrees with the target intrinsically (the
    /// median heat-kernel-signature discrepancy of where its vertices landed, over the
    /// consistency of the functional map that placement implies; the measure that chooses
    /// between starts and stiffnesses), when it was computed: with several rigid starts or a
    /// guided prior. No ground truth is needed, so it can warn of any match (doubtful()).
    std::optional<double> intrinsic_disagreement;
    /// What repair_surface() changed in the template and in the target before they were
    /// matched (RepairedSurface::summary()), empty where nothing: `deformed` is in the
    /// template's vertex order and count all the same.
    std::string template_repairs;
    std::string target_repairs;
    double alignment_seconds = 0;
    double seconds = 0;  ///< everything
    /// Where the time went, stage by stage in the order they ran; each stage the options run
    /// is listed, and one with nothing to do takes no time: "repair" (repair_surface(), and
    /// carrying the result back), "alignment" (rigid starts, scale), "pyramid", "coarsest
    /// analysis" (the coarsest level's signatures and eigenbases), "finest bases", "start
    /// selection" (the rigid starts' selection flows), then either "coarsest flow" (no guided
    /// rounds) or "guided rounds" (with the second opinion's beside them when every match asks
    /// it), "second opinion", "alternative starts", "limb swaps", "prior flow"; per finer level
    /// "refinement" and "refined level checks" (turn-back, fits, limb swaps) on the second
    /// coarsest, "finer flows" on the others; the second reading's own stages from "start
    /// selection" on, named "signatures reading: …", and "signatures reading: judge" (the
    /// commutativity of both readings' maps); "counterparts".
    std::vector<MatchStageTime> stage_times;
    /// True if intrinsic_disagreement is above kDoubtfulDisagreement: the match is likely to
    /// have put parts on the wrong limb.
    [[nodiscard]] bool doubtful() const;
    /// True if the finest level's flow stopped on its own (stagnation or no descent left).
    [[nodiscard]] bool converged() const {
        return !levels.empty() && levels.back().status == FlowStatus::Converged;
    }
};

/// The paper's matcher alone: the flow of eq. 14 in the prior's metric over the multiresolution
/// levels of §6.4, from the inputs as they are placed. Every stage the default adds is off: the
/// global alignment and its rigid starts, the guided coarsest rounds (signatures,
/// eigenfunctions, stretching), the refinement's guided flows, turned-back parts, fits to the
/// fine map, second opinions, alternative starts and limb exchanges. The baseline of the
/// ablation in docs/matching.md; the inputs must share a frame, as in the paper.
[[nodiscard]] MatchOptions paper_match_options();

/// Deforms `template_mesh` onto `target` (another pose of the same subject, any sampling and
/// connectivity) by the flow of the pseudo-Hausdorff distance in the metric of the prior
/// (paper eq. 14): optional global rigid alignment (rigid_alignment_candidates(); with several
/// candidates, each is flowed on the coarsest level and one is kept as MatchOptions::starts
/// describes), then, from the coarsest level to the input, steepest descent with Armijo
/// backtracking and a displacement cap (gradient_descent()), each level started from the coarser
/// one by transfer(). ε is the mean edge length of each level's target.
///
/// A target that shows only part of the template (MatchOptions::partial; by default found by
/// shows_part_only()) is matched as PartialTargetOptions describes: one-sided d_H, every
/// component kept, the template's scale, no intrinsic stages.
///
/// Meshes as they come are matched as repair_surface() makes them (duplicate faces removed,
/// coincident vertices welded, non-manifold vertices and edges split, the largest component);
/// the template's other vertices follow their nearest matched neighbour, so `deformed` keeps
/// the template's vertices and faces. MatchResult::template_repairs says what was repaired.
///
/// \throws InvalidInput if a mesh is empty, has no face, zero area, bad indices or non-finite
///         coordinates, an option is out of range, or the articulated prior lacks a part
///         model that fits the template.
[[nodiscard]] MatchResult match(const TriangleMesh& template_mesh, const TriangleMesh& target,
                                const MatchOptions& options = {});

}  // namespace genflow
