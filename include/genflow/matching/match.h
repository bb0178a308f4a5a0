// SPDX-License-Identifier: MIT
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "genflow/flows/flow.h"
#include "genflow/matching/rigid_alignment.h"
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

/// Above this intrinsic disagreement (MatchResult::intrinsic_disagreement) a match is doubtful.
/// Measured with h1 on the 12 pairs of $GENFLOW_DATA/pairs.json and the 17 of
/// docs/eval/other_poses.json: 0.045–0.24 on every match below 3.7 % mean error; 0.39 and 0.57
/// on the one that failed (TOSCA michael kneeling, 15 % off, an arm on a leg; two
/// simplifications of its target one vertex apart). With the articulated prior, 0.09–0.31 on
/// its 11 results, up to 4 % off.
inline constexpr double kDoubtfulDisagreement = 0.35;

/// Parameters of match(). Every length is relative to the meshes, so the defaults need no
/// tuning per pair (issue 5: scale-free parameters).
struct MatchOptions {
    MatchPrior prior = MatchPrior::H1;
    /// Exponent α of the pseudo-Hausdorff distance and its truncation τ (PseudoHausdorffOptions:
    /// the relative error of d_H is then below τ/(2α) = 6e-4, far below what a flow notices);
    /// ε is the target's mean edge length (docs/formulas.md §8: smaller makes vertices snap
    /// tangentially).
    double alpha = 8;
    double truncation = 1e-2;
    /// Multiresolution (paper §6.4, docs/formulas.md §9): the flow runs on QEM-coarsened template
    /// and target first, then on finer levels, each started from the coarser result carried over by
    /// rotation-interpolated offsets. `levels` = 0 chooses them: the coarsest has about
    /// `coarse_vertices`, each finer one 4× more, up to the input. Each target level is the target
    /// coarsened by the template's factor, to no fewer than half the template level's vertices.
    int levels = 0;
    Eigen::Index coarse_vertices = 1000;
    /// An ε schedule (issue 5): the first half of the coarsest level's steps flows d_H with ε
    /// this many times larger, whose landscape is smoother, then the level's own ε. Measured
    /// (h1, mean error): FAUST small 3.1 → 1.5 % and centaur small 3.9 → 3.3 % at 5, but the
    /// generated demo limb (articulated, 6 candidates) 2.5 → 4.4 % (12.5 % at 3): it moves
    /// matches between basins, not always towards the right one, so it is off by default.
    double coarse_epsilon = 1;
    /// At most this many steps on the coarsest level, and on each finer one. The finer levels
    /// only polish the carried-over match: 15 steps instead of 40 left the mean correspondence
    /// error unchanged to ±0.1 % without parts (all pairs of docs/eval/results.md; articulated
    /// makehuman body 3.1 → 3.5 %) and the mean surface distance within ±0.1 % of the
    /// diagonal, at half the time (TOSCA cat 28K, h1: 17.8 → 7.5 s).
    int max_iterations = 300;
    int fine_iterations = 15;
    /// No vertex moves farther than this fraction of the target's bounding-box diagonal in one
    /// step (docs/formulas.md §9: 2 %).
    double max_step = 0.02;
    /// Implicit steps (DescentOptions::implicit, paper eq. 11) instead of explicit ones. Measured
    /// (FAUST and centaur small): the coarsest level converges in 58–93 steps instead of 300,
    /// 40 % less time, errors within ±0.3 % (h1 3.0 → 3.1 %, 3.9 → 4.1 %; rigid 4.5 → 4.9 %,
    /// 6.4 → 5.9 %): faster, not better, so off by default. Again on whole h1 matches
    /// (results.md, "Flows that stop sooner"): the 12 pairs 174 → 137 s
    /// at 1.04 %, the TOSCA cat 7.4 s, but the held-out sets worse (0.81 → 0.86 %, 0.75 →
    /// 0.83 %), their near-tied choices going the other way.
    bool implicit = false;
    /// Converged when d_H fell by less than this fraction over the last 20 steps. Most of the
    /// coarsest level's flows creep on by 0.2–0.5 % per 25 steps until max_iterations; 3e-3
    /// stops them sooner and makes matches 15–30 % faster at about the same mean error (h1 on
    /// the 12 pairs of docs/eval/results.md: 174 → 123 s, 1.04 %), but the choices between
    /// contenders that tie then go either way, some results better and some worse (results.md,
    /// "Flows that stop sooner"): a trade a user may make, not the default.
    double stagnation_tolerance = 1e-3;
    /// Start from a global rigid alignment (so inputs need no pre-alignment). Between
    /// articulated poses the best rigid fit is often a flipped one (the TOSCA cat and horse
    /// head to tail), and after a flow a flipped start can fit the target's surface about as
    /// closely as the right one. So the best `alignment_candidates` distinct rigid starts each
    /// flow `selection_iterations` steps on the coarsest level, and d_H only shortlists them:
    /// of the starts whose d_H is within `selection_tolerance` of the lowest, the one whose
    /// correspondence agrees best with the target intrinsically goes on and flows in the prior's
    /// metric: the lowest median discrepancy of the heat kernel signatures at the points it
    /// reached, divided by how nearly the correspondence preserves the 20 lowest Laplacian
    /// eigenfunctions (detail::SpectralDescriptors::map_consistency()).
    ///
    /// The selection flows run in the H1 metric whatever the prior: it lets the template reach
    /// the target's surface, so that the signatures are compared at the right places. After
    /// flows of the match's own prior, which may fit worse, the choice was wrong on 5 of the
    /// 52 runs of docs/eval/results.md (L2 centaur, rigid cat and small centaur, isometric
    /// small cat, articulated FAUST) where the H1 flows chose rightly. Measured on the 12 pairs
    /// of $GENFLOW_DATA: the lowest rigid-fit d_H picks the right start on 8 pairs, the lowest
    /// d_H after the flows on 8, the shortlist by the signatures alone on 11, with the map's
    /// consistency on 12. The signatures alone missed TOSCA michael: they preferred a start
    /// turned front to back (0.44 against 0.47; 13 % error at the coarsest level against 6 %),
    /// whose map is less consistent (0.78 against 0.88; on the other pairs the right start's
    /// is the highest or within 0.05 of it, and its discrepancy the lowest by far).
    bool align = true;
    int alignment_candidates = 6;
    int selection_iterations = 300;
    double selection_tolerance = 0.05;
    /// With the guided rounds (signature_guidance; h1, articulated, isometric), a start that agreed
    /// about as well after the selection flows may end better: the libigl arm's chosen start
    /// is twisted about the arm (disagreement 0.42 against 0.48 for the right one; 6.7 % mean
    /// error at the end against 2.1 %), and the rounds that follow tell them apart (0.25
    /// against 0.16). So the shortlisted starts whose disagreement is within
    /// `contender_tolerance` of the lowest, at most `contenders` of them, each go through the
    /// guided rounds, and the one that ends with the lowest disagreement is kept. 1 turns this
    /// off. Measured on the 12 pairs of $GENFLOW_DATA, h1: the arm 6.72 → 2.13 %; contenders on
    /// TOSCA michael (1.07 of the lowest; its rival ends at 0.19 against 0.12) and the hand
    /// (1.20; 0.21 against 0.18) lost, rightly; no other pair had one within 0.25 (the nearest:
    /// FAUST 1.35). Articulated: hand 3.87 → 3.66 % (the rival kept), arm 7.11 → 6.53 %. The
    /// contenders run side by side: 1–1.7 s more where there is one.
    int contenders = 2;
    double contender_tolerance = 0.25;
    /// Guidance of the coarsest flow by the heat kernel signatures: that flow first runs (up to
    /// max_iterations steps, from the chosen rigid start) on the d_H of template and target
    /// points augmented with their log signatures (PointDescriptors), then on the plain d_H.
    /// d_H alone lets a limb settle on whatever surface is nearest (FAUST's hanging arms
    /// fitted onto the hips: 26 % of the vertices, 5.5 % mean error); with the signatures a
    /// point is near only to points that are both close and alike. The weight is the distance,
    /// as a fraction of the target's diagonal, between two points one standard deviation of the
    /// template's log signatures apart at every time; 0 turns the guidance off. Measured on the
    /// 1000-vertex levels of the 9 full pairs of $GENFLOW_DATA (H1): the mean error falls on
    /// every pair (FAUST 3.8 → 1.5 %, makehuman body 4.3 → 1.6 %, centaur 3.9 → 2.1 %, wolf
    /// 1.6 → 1.1 %); weights of 0.05 and 0.2 gain less. Guided are the h1, articulated and
    /// isometric priors (articulated, with the eigenfunctions: makehuman body 3.4 → 1.1 %, FAUST
    /// 6.8 → 2.2 %, hand 9.6 → 4.1 %). The quasi-isometric prior's guided rounds flow in the H1
    /// metric, and the kept result then flows up to max_iterations steps in its own: its own rounds
    /// end too far from the target for their disagreement to tell a front-to-back result from
    /// the right one (TOSCA michael 0→1 was kept front to back, 18.9 % off). So guided, the 12
    /// pairs of $GENFLOW_DATA went from 1.8–10.3 % to 0.4–2.5 % (horse 7.6 → 1.1 %, michael
    /// 7.2 → 0.4 %), and the bent test limb's mean edge strain from 0.034 to 0.065, still below
    /// L2's 0.20. Not the quasi-rigid prior: the guidance pulled a rigidly moved limb 7 % off
    /// (the signatures of two samplings differ, and a rigid motion is all that flow can change to
    /// meet them); L2 stays the unguided baseline.
    double signature_guidance = 0.1;
    /// Then the guidance by the eigenfunctions (with signature_guidance only): the signatures
    /// are blind to a shape's symmetries, and a left paw may land on the right one (wolf, horse,
    /// cat). The low eigenfunctions of the Laplacian tell left from right, and a functional map
    /// estimated from the signature-guided match carries the template's onto the target's
    /// (detail::SpectralDescriptors::eigenfunction_descriptors()); the coarsest level flows once
    /// more from the chosen rigid start, on the d_H augmented with them, then on the plain d_H.
    /// The weight is the root-mean-square spread of the target's descriptors as a fraction of
    /// its diagonal; 0 turns this second guidance off. Measured on the full pairs of
    /// $GENFLOW_DATA (h1, mean error): TOSCA cat 9.2 → 3.6 %, horse 4.2 → 1.4 %, hand
    /// 5.1 → 3.1 %, centaur 2.4 → 1.2 %, makehuman body 1.9 → 1.1 %, wolf 1.3 → 0.9 % (its paw
    /// back on its own side), at 0.5–2 s more (docs/eval/results.md). The map is estimated
    /// from the signature-guided match and from the start's selection flow, by ZoomOut from
    /// several sizes each, keeping the most nearly orthogonal map that moves the placement least
    /// (detail::SpectralDescriptors::eigenfunction_descriptors()): from one, ZoomOut ended at a
    /// wrong map on some coarse meshes and not on others one vertex larger (TOSCA cat 2.0–8.9 %
    /// over six such pyramids, now 1.9–2.0 %; the libigl arm 1.6–3.9 %, now 1.3–2.3 % but
    /// 3.9 % on one).
    double eigenfunction_guidance = 0.1;
    /// How strongly the eigenfunctions should guide depends on the pair, as the stiffness does
    /// (stiffness_candidates): the last round can also run at eigenfunction_guidance × 2^j for
    /// j < guidance_candidates (each with every stiffness, all side by side), keeping the
    /// result that disagrees least with the target. Off (1) by default: with 2, on the 12 pairs
    /// of $GENFLOW_DATA (h1, mean error) hand 2.25 → 1.78 %, arm 2.13 → 1.91, FAUST 1.38 →
    /// 1.31, makehuman body 0.61 → 0.57, small centaur 1.07 → 0.95, wolf 0.55 → 0.53, horse
    /// 1.00 → 0.95, small FAUST 0.81 → 0.83, but the generated bent limb of the benchmark
    /// 2.30 → 2.83 %, the horse's Hausdorff 0.96 → 3.09 % (a fold at an ear, kept on a near
    /// tie: 0.1704 against 0.1707) and the body's 0.78 → 1.91 %, at 1.5–6 s more.
    int guidance_candidates = 1;
    /// The eigenfunctions are carried over by a map fitted to the signature-guided match, and
    /// where that match was poor they can guide a part onto itself back to front: TOSCA
    /// michael kneeling to standing (h1) ended with his torso's front on its back, which
    /// neither d_H nor the edges' lengths see (a reflection keeps both). A last round whose
    /// result is doubtful (disagreement above kDoubtfulDisagreement) runs again, at every
    /// stiffness, guided by the signatures alone, and that result is kept if it disagrees less
    /// (MatchResult::signature_fallback). The signatures cannot tell left from right; the
    /// check for swapped limbs that follows (swap_limbs) can, and matches again from the
    /// exchanged places with the signatures alone too. Only where
    /// eigenfunction_guidance > 0; results that are not doubtful are unchanged.
    bool signature_fallback = true;
    /// The last guided round (the eigenfunctions', else the signatures') flows on d_H plus
    /// stretch_weight × the target's diagonal × the EdgeLengthEnergy of the coarsest template
    /// level at its rigid start: d_H cannot see where along the target's surface a point lands,
    /// and without it the coarsest template slid tangentially until its edges were stretched or
    /// squeezed by 40–50 % on average (TOSCA cat, MakeHuman hand; 8–14 % between the true
    /// poses), which is most of the remaining correspondence error: with the true positions
    /// on the coarsest level the finer levels end 0.2–0.5 % from the truth. 0 turns it off.
    /// Measured on the 12 pairs of $GENFLOW_DATA (h1, mean error, 0 → 0.1): TOSCA cat 3.63 →
    /// 2.67 %, wolf 0.92 → 0.55, makehuman body 1.14 → 0.72, horse 1.43 → 1.00, hand 3.08 →
    /// 2.56, centaur 1.17 → 0.82, FAUST 1.64 → 1.38, arm 7.22 → 6.72, small cat, FAUST and
    /// centaur 2.55 → 2.41, 1.22 → 0.88, 1.38 → 1.07; michael 3.62 → 3.82; at the same time.
    /// Weights of 0.03–0.2 gave about the same; 0.4 turned the cat's head (4.4 %). In the
    /// first round as well, it spoilt the functional map that round serves to estimate (cat
    /// 9.5 % at 0.1); in the guided flow only, the plain flow after it slid again (wolf 0.83 %,
    /// small FAUST 1.22 %). The price: the coarsest template fits the surface less closely
    /// where the poses are not isometric at its scale, and 15 fine steps leave the cat's
    /// symmetric Hausdorff distance at 4.8 % of the diagonal instead of 2.2 % (mean surface
    /// distance 0.2 → 0.5 %; the other pairs within ±0.4 %).
    double stretch_weight = 0.1;
    /// How stiff the last guided round should be depends on the pose change: too soft, a part
    /// the guidance pulls wrongly turns (TOSCA michael's head, nodded forward 40°, ended turned
    /// about the neck); too stiff, a part that should bend cannot (the cat's head at 0.4). So
    /// that round runs at stretch_weight × 4^k for k < stiffness_candidates; a stiffer one,
    /// after its plain flow, flows once more at stretch_weight (the parts it placed settle on
    /// the surface), and the result whose correspondence disagrees least with the target
    /// intrinsically is kept (the criterion that chooses among rigid starts). 1 runs
    /// stretch_weight only. Measured on the 12 pairs of $GENFLOW_DATA (h1, mean error, 1 → 3):
    /// michael 3.82 → 1.13 %, hand 2.56 → 2.25, makehuman body 0.72 → 0.61, small FAUST 0.88 →
    /// 0.81, the others unchanged (within 0.01). The candidates flow side by side on the OpenMP
    /// threads: 0.4–0.6 s more on two cores (1–3 s one after the other). (A softer candidate,
    /// 0.025, won the criterion on the arm and lost 0.2 % there.)
    int stiffness_candidates = 3;
    /// The coarsest level is small (a few hundred vertices: 471 on the TOSCA cat), and where it
    /// puts the template along the target's surface fixes most of the final error: the finer
    /// levels' flows on d_H cannot see tangential sliding (0 fine steps instead of 15 changes
    /// the mean error by 0.1 %). So the next finer level is refined as the coarsest was: the
    /// functional map is estimated once more from the coarsest result and, for each of
    /// eigenfunction_guidance × 2^-j, j < refinement_guidances, that level flows
    /// `refinement_iterations` steps on the d_H augmented with the eigenfunctions (and the kept
    /// stretch weight) before its plain flow; of those results and the plain flow alone, the
    /// one whose coarsest vertices disagree least with the target intrinsically is kept
    /// (guided matches with eigenfunction_guidance only; 0 turns this off).
    /// The refining flows run side by side. Measured on the 12 pairs of $GENFLOW_DATA (h1,
    /// mean error): hand 2.25 → 1.90 %, libigl arm 2.13 → 1.64, small cat 2.41 → 1.79,
    /// makehuman body 0.61 → 0.52, the others within 0.01 (the TOSCA cat kept its plain flow:
    /// guided, its raised front leg went further off, 3.2 %); 0.4–0.7 s more on the full pairs.
    /// 100 steps, or the third coarsest level refined too, gained on the arm and lost on the
    /// hand (docs/eval/results.md).
    int refinement_guidances = 2;
    int refinement_iterations = 50;
    /// After the refinement above, turn back the parts the match put turned over in their own
    /// place (an extremity palm for back): nothing extrinsic sees a cylinder's turn about its
    /// axis, but a functional map of 60 eigenfunctions, refined by ZoomOut from the level's own
    /// correspondence, sees a thumb. Where it disputes the match over a part larger than it
    /// resolves (1/60 of the area) by a turn of more than 90° that is not a reflection, the
    /// part is turned as the map places it, the rest of the disputed region by the share of
    /// that turn the map asks for, and the level flows again (`refinement_iterations` steps,
    /// with the stretch weight); kept if its d_H ends within 25 % of the unturned one's.
    /// TOSCA michael's hands (turned 164° and 171°): mean error 1.13 → 0.43 %, area turned over
    /// 5.7 → 3.1 %, Hausdorff distance 0.85 → 1.5 % (faces stretched at the elbows, where the
    /// forearms untwist); no other pair of $GENFLOW_DATA changes (docs/eval/results.md).
    /// Same matches as the refinement; MatchResult::turned_parts says how many were turned.
    bool turn_back_parts = true;
    /// After that, draw the refined level towards where the same map puts each vertex by a
    /// smooth step (H1 over 1 % of the diagonal; not where the map tears off pieces smaller than
    /// it resolves), flow again (`refinement_iterations` steps, with the stretch weight), and
    /// keep the result if the heat kernel signatures then agree better with the target's, or
    /// the turning functions clearly better with the signatures at most 10 % worse, and the
    /// turning functions do not say the map was mirrored (src/matching/map_fit.h: TOSCA michael
    /// standing to kneeling 5.1 → 2.7 %, the libigl elephant rest to frame 300 3.6 → 1.4 %,
    /// h1); then again, with the map ZoomOut finds from the fitted level,
    /// up to `map_fits` fits in all, as long as each lowers the signatures' discrepancy by more
    /// than 5 % (0: no fit). On the 43 h1 and articulated results of docs/eval/results.md the
    /// first fit was kept on 20: better on 18 (hand 1.94 → 1.29 %, articulated 3.09 → 1.58 %;
    /// FAUST 000→003 articulated 3.25 → 1.31 %, the elephant's frame 300 2.87 → 1.40 %),
    /// 0.02–0.03 worse on two. Further fits unwind what a single map only starts to: the libigl
    /// arm's upper arm, turned about its axis (articulated, 4.04 → 3.11 % after one fit, 1.89 %
    /// after four), though it ends with a larger Hausdorff distance (1.5 → 4.0 %: faces stretched
    /// across the elbow). MatchResult::map_fits says how many fits were kept.
    int map_fits = 6;
    /// A second opinion for guided matches (h1, articulated, isometric): the guided rounds of the
    /// coarsest level again, from a start found without the flow (the shapes' extremities matched
    /// by their geodesic distances, a functional map fitted to them, the template at the shapes'
    /// area ratio turned and moved onto where that map puts it; src/matching/intrinsic_start.h),
    /// whose placement also serves to estimate the eigenfunctions' map. Its result is kept if it
    /// disagrees clearly less with the target, by a quarter, than the rigid starts' best, or
    /// less with the turning functions of pairs of extremities agreeing about as well, within
    /// 0.05 (MatchResult::second_opinion): the disagreement ranks results far apart well, not
    /// near ties (FAUST 003→000, articulated: front to back from the intrinsic start at 0.33, 17 %
    /// off at the coarsest level, against 0.40 for the rigid start's 4.4 %; its turning
    /// functions 0.37 against 0.50). Near a tie, where they agree alike, the intrinsic start's
    /// result is the better one more often than not (the libigl arm rest→pose3: 2.15 → 1.07 %). At
    /// 0, the default, it is asked of every match and contends side by side with the rigid starts'
    /// guided rounds; above 0, only of results whose disagreement is above this, after them; +∞
    /// never. TOSCA michael kneeling (h1): 15.3 → 3.5 % mean error (1.1 % since the start keeps his
    /// size). Side by side it cost 1.23 times the time on the 12 h1 pairs of pairs.json (one after
    /// the other, as at kDoubtfulDisagreement, 1.45 times where it runs).
    double second_opinion_above = 0;
    /// A result still doubtful after the second opinion (intrinsic disagreement above
    /// kDoubtfulDisagreement), or one the second opinion gave, is matched again from the
    /// intrinsic starts of up to this many of the next landmark sets (detail::intrinsic_starts():
    /// by how well their maps keep the orientation), side by side; the one that disagrees least
    /// is kept (MatchResult::alternative_start). The preferred set is often a mirror image where
    /// the pose breaks the symmetry the orientation test relies on: TOSCA michael standing to
    /// kneeling (1→2) was matched front to back, 22.6 % mean error, though not doubtful (0.27);
    /// from the next set 0.24. A result from the second opinion rests on that set alone, so
    /// the next ones are tried for it below kDoubtfulDisagreement too, down to
    /// alternative_starts_above. Needs the second opinion (second_opinion_above); 0 = none.
    int alternative_starts = 3;
    /// The disagreement above which a result the second opinion gave is matched again from the
    /// alternative starts (a doubtful result always is); 0 = every one. Below the lowest that a
    /// wrong match reached on the h1 matches of docs/eval (TOSCA michael 0→1 from starts turned
    /// front to back, 0.19; michael 1→2's front-to-back second opinion, 0.27, is still matched
    /// again). Of those 45 matches, 14 kept a second opinion below it; their alternative starts
    /// ended within 0.005 of it, none clearly better, so it stands: such a match takes about
    /// half the time (makehuman body rest→pose1 29.9 → 15.4 s, TOSCA michael 0→1 47.6 →
    /// 30.4 s), and its mean error moved by −0.03 … +0.16 % (libigl arm rest→pose3 1.07 →
    /// 1.23 %; unchanged on 8 of the 14).
    double alternative_starts_above = 0.15;
    /// Limbs put on each other's places: a template whose stride puts its left leg where the
    /// target has its right one is matched with the two exchanged, and neither d_H nor the
    /// heat kernel signatures tell. The turning functions of pairs of extremities do (they
    /// change sign under a reflection; src/matching/swapped_limbs.h): if exchanging where the
    /// kept result put two extremities makes them agree clearly better with the target's, the
    /// result is drawn towards the map of the exchanged extremities and matched again by the
    /// guided rounds, and kept if its own functions agree clearly better
    /// (MatchResult::swapped_limbs). Needs the second opinion (its analyses of the shapes).
    /// The refined level (refinement_guidances) is checked the same way after its fits to the
    /// fine map, and flowed again from the exchanged places: a limb the coarsest level turned
    /// onto another's place about its joint (the articulated prior) keeps the surface's
    /// orientation, and the fits reflect it into a place the turning functions tell.
    bool swap_limbs = true;
    RigidAlignmentOptions alignment;
    /// Penalties of the quasi-rigid prior.
    QuasiRigidOptions rigid;
    /// The template's parts (required by the articulated prior; joint centres in the
    /// template's own frame), and the prior's penalties.
    std::optional<PartModel> parts;
    QuasiArticulatedOptions articulated;
    /// The articulated prior's penalty of the global rigid motion on the finest level, in
    /// (0, 1], in place of `articulated.global` (1: that motion costs what any other does). The
    /// finest level's short flow polishes a pose the coarser levels settled; boosted there,
    /// each explicit step was mostly the whole template moving, which the backtracking on d_H
    /// accepts up to about twice as far as d_H's minimum along it: FAUST 001→002
    /// (docs/eval/posed_templates.json) shifted 0.1–0.4 % of the diagonal back and forth at
    /// every step, 1.70 → 2.07 % mean error over the level. At 1: 1.73 %, and the 22
    /// articulated rows of docs/eval 1.006 → 0.977 % on average (12 better, 5 worse by
    /// 0.04 % at most). Unboosted on the refined level too, the libigl arm rest→pose2 went
    /// 1.93 → 3.16 %: its fits to the fine map need the prior there.
    double articulated_finest_global = 1;
    /// Parameters of the quasi-isometric prior (rigidity length relative to the diagonal). G is
    /// rebuilt every 4th step: 2.2× faster on the centaur (24 → 11 s), errors unchanged to
    /// ±0.05 % on the small pairs.
    QuasiIsometricOptions isometric{.refresh_interval = 4};
    /// H1 smoothing length as a multiple of the template's mean edge length: λ = (k·h)².
    double h1_length = 5;
    /// Called after every step; return false to stop. Optional. Where a level runs independent
    /// flows side by side (the rigid starts, the stiffness candidates, the refining flows), one of
    /// them reports, possibly from another thread than the caller's, and the others stop when
    /// it is told to: the callback is never called twice at once.
    std::function<bool(const MatchProgress&)> progress = {};
    /// Called with each level's result after each stage (MatchStage), from the calling thread.
    /// Optional; it does not change the match.
    std::function<void(const MatchStage&)> stages = {};
};

/// One level of a match, coarsest first in MatchResult::levels.
struct MatchLevel {
    Eigen::Index template_vertices = 0;
    Eigen::Index target_vertices = 0;
    /// Steps of all the level's flows (a guided coarsest level has several, a refined second
    /// coarsest level one plain and two per refining guidance).
    int iterations = 0;
    FlowStatus status = FlowStatus::MaxSteps;
    double energy_start = 0;  ///< d_H at the start of the level's flow
    double energy_end = 0;
    double seconds = 0;  ///< pyramid, transfer and flow of this level
};

/// What match() did, for the report.
struct MatchResult {
    TriangleMesh deformed;           ///< the template, deformed (its connectivity unchanged)
    Similarity initial_alignment;    ///< the rigid start (identity without `align`)
    std::vector<MatchLevel> levels;  ///< coarsest first
    double hausdorff_energy = 0;     ///< final d_H on the finest level
    /// The stretch weight of the kept last guided round (MatchOptions::stiffness_candidates);
    /// 0 when no guided round had the stretching energy.
    double stretch_weight = 0;
    /// The eigenfunction guidance of the kept last round (MatchOptions::guidance_candidates);
    /// 0 without it.
    double eigenfunction_guidance = 0;
    /// Whether the kept last round was guided by the signatures alone
    /// (MatchOptions::signature_fallback); its eigenfunction_guidance is then 0.
    bool signature_fallback = false;
    /// The eigenfunction guidance of the kept refining flow of the second coarsest level
    /// (MatchOptions::refinement_guidances); 0 when its plain flow was kept or none ran.
    double refinement_guidance = 0;
    /// How many parts MatchOptions::turn_back_parts turned back.
    int turned_parts = 0;
    /// How many fits to the fine map were kept (MatchOptions::map_fits).
    int map_fits = 0;
    /// The intrinsic disagreement of the second opinion (MatchOptions::second_opinion_above),
    /// if one was given, and whether its result was kept.
    std::optional<double> second_opinion_disagreement;
    bool second_opinion = false;
    /// How many intrinsic starts of further landmark sets were tried
    /// (MatchOptions::alternative_starts), and which was kept (its rank, 1 = the first after
    /// the second opinion's; 0 = none).
    int alternative_starts = 0;
    int alternative_start = 0;
    /// How many pairs of limbs MatchOptions::swap_limbs exchanged, at the coarsest and the
    /// refined level (0 if no match from the exchanges was kept, or none was tried). The other
    /// fields say where the coarsest result it started from came from.
    int swapped_limbs = 0;
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
/// candidates, each is flowed on the coarsest level and one is kept as MatchOptions::align
/// describes), then, from the coarsest level to the input, steepest descent with Armijo
/// backtracking and a displacement cap (gradient_descent()), each level started from the coarser
/// one by transfer(). ε is the mean edge length of each level's target.
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
