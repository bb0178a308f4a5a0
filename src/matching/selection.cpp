// SPDX-License-Identifier: MIT
#include "matching/selection.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "genflow/matching/match.h"

namespace genflow::detail {

double disagreement(const SpectralDescriptors& spectral, const Eigen::MatrixX3d& deformed) {
    return spectral.discrepancy(deformed) / spectral.map_consistency(deformed);
}

bool is_doubtful(double disagreement) {
    return disagreement > kDoubtfulDisagreement;
}

std::size_t choose_start(const std::vector<FlowResult>& flows, const SpectralDescriptors& spectral,
                         double tolerance) {
    if (flows.size() < 2) {
        return 0;
    }
    double lowest = std::numeric_limits<double>::infinity();
    for (const FlowResult& flow : flows) {
        lowest = std::min(lowest, flow.energy.back());
    }
    std::size_t chosen = 0;
    double least = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < flows.size(); ++k) {
        if (flows[k].energy.back() <= (1 + tolerance) * lowest) {
            const double value = disagreement(spectral, flows[k].mesh.V);
            if (value < least) {
                least = value;
                chosen = k;
            }
        }
    }
    return chosen;
}

KeptFlow keep_lowest(const std::vector<FlowResult>& flows, const std::atomic<bool>& cancelled,
                     const std::function<double(const FlowResult&)>& rate) {
    KeptFlow kept;
    for (std::size_t k = 0; k < flows.size(); ++k) {
        kept.steps += flows[k].steps;
        const double value = rate(flows[k]);
        if (k == 0 || (!cancelled && value < kept.rating)) {
            kept.rating = value;
            kept.index = k;
        }
    }
    return kept;
}

bool replaces(const Score& challenger, const Score& kept) {
    const double less = challenger.disagreement;
    const double more = kept.disagreement;
    if (challenger.start == StartKind::Rigid || kept.start == StartKind::Intrinsic) {
        return less < more;
    }
    return less < (1 - kIntrinsicMargin) * more ||
           (less < more && challenger.turning() >= kept.turning() - kIntrinsicTurning);
}

bool needs_signature_fallback(double disagreement) {
    return is_doubtful(disagreement);
}

bool needs_second_opinion(double disagreement, double second_opinion_above) {
    return second_opinion_above > 0 && disagreement > second_opinion_above;
}

bool needs_alternative_starts(double disagreement, double alternative_starts_above) {
    return is_doubtful(disagreement) || disagreement > alternative_starts_above;
}

bool keeps_limb_exchange(const LimbExchange& exchange) {
    return (!exchange.drift || *exchange.drift <= kLimbSwapDrift) &&
           exchange.agreement_after >= kLimbSwapAgreement &&
           exchange.agreement_after > exchange.agreement_before + kLimbSwapMargin &&
           exchange.disagreement_after <=
               (1 + kLimbSwapDisagreement) * exchange.disagreement_before;
}

bool keeps_turned_back(double distance_after, double distance_before) {
    return distance_after <= kTurnBackAllowance * distance_before;
}

bool keeps_signatures_reading(const ReadingScore& reading, const ReadingScore& first) {
    return reading.commutativity < first.commutativity;
}

}  // namespace genflow::detail
