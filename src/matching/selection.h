// SPDX-License-Identifier: MIT
// How the matcher judges its candidate results, in one place: the score a candidate gets (its
// intrinsic disagreement with the target, and the turning functions' agreement where a tie
// needs it) and the named rules that keep one candidate or reject another. The stages run the
// flows; only these rules compare their numbers. The constants' measurements are in
// docs/matching.md ("Keep and reject rules").
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "genflow/flows/flow.h"
#include "matching/spectral_descriptors.h"
#include "matching/swapped_limbs.h"

namespace genflow::detail {

/// How far a placement of the coarsest template disagrees with the target intrinsically: the
/// median signature discrepancy over the map's consistency with the eigenbases. Lower is
/// better; above kDoubtfulDisagreement a result is doubtful.
[[nodiscard]] double disagreement(const SpectralDescriptors& spectral,
                                  const Eigen::MatrixX3d& deformed);

/// Whether a result's disagreement makes it doubtful (kDoubtfulDisagreement, match.h).
[[nodiscard]] bool is_doubtful(double disagreement);

/// Of the flows from the rigid starts whose final d_H is within `tolerance` of the lowest, the
/// one that disagrees least (MatchOptions::starts).
[[nodiscard]] std::size_t choose_start(const std::vector<FlowResult>& flows,
                                       const SpectralDescriptors& spectral, double tolerance);

/// Of flows run side by side, the one whose rating is lowest, its rating, and the steps of them
/// all. Once cancelled, the first (the one that reported): the others may have stopped
/// anywhere.
struct KeptFlow {
    std::size_t index = 0;
    double rating = 0;
    int steps = 0;
};
[[nodiscard]] KeptFlow keep_lowest(const std::vector<FlowResult>& flows,
                                   const std::atomic<bool>& cancelled,
                                   const std::function<double(const FlowResult&)>& rate);

/// Where a candidate of the coarsest level started from.
enum class StartKind { Rigid, Intrinsic };

/// A candidate of the coarsest level as the rules see it: where it started, its disagreement,
/// and its turning functions' agreement with the target's (swapped_limbs.h), computed only if
/// a rule asks (it needs the shapes' intrinsic analyses; 0 without them).
struct Score {
    StartKind start = StartKind::Rigid;
    double disagreement = 0;
    std::function<double()> turning = [] { return 0.0; };
};

/// How much less an intrinsic start's result must disagree than a rigid start's to replace it
/// outright (MatchOptions::second_opinion).
inline constexpr double kIntrinsicMargin = 0.25;
/// Near a tie, an intrinsic start's result that disagrees less replaces a rigid start's if its
/// turning functions agree at least about as well, within this.
inline constexpr double kIntrinsicTurning = 0.05;

/// Whether `challenger` goes on instead of `kept`: it disagrees less; an intrinsic start's
/// result against a rigid start's, clearly less (kIntrinsicMargin) or less with its turning
/// functions agreeing about as well (kIntrinsicTurning): the disagreement ranks results far
/// apart well, but not near ties, where the turning functions tell left from right.
[[nodiscard]] bool replaces(const Score& challenger, const Score& kept);

/// Whether a result is matched again guided by the signatures alone
/// (MatchOptions::guided.signature_fallback): it is doubtful.
[[nodiscard]] bool needs_signature_fallback(double disagreement);

/// Whether a result asks for the intrinsic start's second opinion after the rigid starts'
/// rounds (MatchOptions::second_opinion > 0): it disagrees more than that.
[[nodiscard]] bool needs_second_opinion(double disagreement, double second_opinion_above);

/// Whether a result is matched again from the next landmark sets' intrinsic starts
/// (MatchOptions::second_opinion.alternative_starts): it is doubtful, or disagrees more than
/// `alternative_starts_above`, whichever start it came from.
[[nodiscard]] bool needs_alternative_starts(double disagreement, double alternative_starts_above);

/// How much an exchange of two limbs' places must raise the turning functions' agreement to
/// be tried, and the match from it to be kept (MatchOptions::limb_swaps).
inline constexpr double kLimbSwapMargin = 0.05;
/// How well the turning functions must then agree, as right maps do.
inline constexpr double kLimbSwapAgreement = 0.4;
/// How much more the match from the exchange may disagree: the signatures cannot tell left
/// from right, so an exchange back leaves the disagreement about where it was.
inline constexpr double kLimbSwapDisagreement = 0.1;

/// How far from its exchanged place the match may put an exchanged extremity (√area units):
/// twice the extremity radius.
inline constexpr double kLimbSwapDrift = 2 * kExtremityRadius;

/// A result with limbs on each other's places, before and after its match from the exchanged
/// places; `drift` is how far that match put an exchanged extremity from its exchanged place
/// (exchange_drift()), where the check asks it.
struct LimbExchange {
    double agreement_before = 0;
    double agreement_after = 0;
    double disagreement_before = 0;
    double disagreement_after = 0;
    std::optional<double> drift = std::nullopt;
};

/// Whether the match from exchanged limbs is kept: its extremities stayed where they were put
/// (if asked), its turning functions agree as a right map's do and clearly better than before,
/// and its signatures about as well.
[[nodiscard]] bool keeps_limb_exchange(const LimbExchange& exchange);

/// What the judge of the readings (signatures_reading.h) reads of a reading's map.
struct ReadingScore {
    /// laplacian_commutativity(): lower for a map nearer an isometry.
    double commutativity = 0;
    /// orientation_ratio(): above 1 the map reverses the surface's orientation. None where the
    /// spectra it needs could not be had.
    std::optional<double> orientation_ratio;
};

/// Whether the signatures' reading replaces the first (MatchOptions::signatures_reading): its map
/// commutes better with the Laplacians, which tells a right map from one off as a whole where
/// the disagreement cannot (docs/matching.md, "The signatures' reading"). The orientation is
/// reported, not judged: on the development sample no kept map reversed it, and most maps off
/// as a whole lay the body turned about, which keeps it (docs/benchmarks.md, "The readings off
/// as a whole lie turned about, not reflected").
[[nodiscard]] bool keeps_signatures_reading(const ReadingScore& reading, const ReadingScore& first);

/// How much higher d_H may end after parts were turned back and flowed again
/// (MatchOptions::turn_back): "about as low", a quarter's allowance.
inline constexpr double kTurnBackAllowance = 1.25;

/// Whether the level with its turned-over parts turned back is kept.
[[nodiscard]] bool keeps_turned_back(double distance_after, double distance_before);

}  // namespace genflow::detail
