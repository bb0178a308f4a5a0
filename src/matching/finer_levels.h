// SPDX-License-Identifier: MIT
// The matcher's finer levels (paper §6.4): each carries the coarser result to its own
// resolution and flows it a few steps. In a guided match the second coarsest is refined and
// checked: flows guided by the eigenfunctions beside the plain one, parts a fine functional map
// places turned over turned back, fits to that map, and limbs put on each other's places
// exchanged; each has its own switch and is kept only by its rule (selection.h, map_fit.h).
#pragma once

#include <atomic>
#include <optional>
#include <vector>

#include "genflow/flows/flow.h"
#include "genflow/matching/match.h"
#include "matching/fine_spectrum.h"
#include "matching/level_flow.h"
#include "matching/prepare.h"
#include "matching/spectral_descriptors.h"
#include "matching/stopwatch.h"
#include "matching/swapped_limbs.h"

namespace genflow::detail {

/// The finest level's result and what the finer levels chose (as MatchResult reports it).
struct FinerMatch {
    Eigen::MatrixX3d deformed;  ///< the template's vertices, deformed, at the input's resolution
    std::vector<MatchLevel> levels;  ///< per level flowed, coarser first
    double refinement_guidance = 0;
    int turned_parts = 0;
    int map_fits = 0;
    int swapped_limbs = 0;
};

class FinerLevels {
public:
    /// The finer levels of `pyramid`, from the coarsest level's result `coarsest` placed at
    /// rest by `start`, which kept `stretch_weight`. `spectral` analyses the coarsest level; it
    /// is needed in guided matches (runs_guided_rounds()), else may be null. All are kept by
    /// reference. `diagonal`: the target's bounding-box diagonal.
    FinerLevels(const std::vector<Level>& pyramid, const LevelFlows& flows,
                const SpectralDescriptors* spectral, const MatchOptions& options, double diagonal,
                const std::atomic<bool>& cancelled, const Similarity& start, double stretch_weight);

    /// The levels below the coarsest, from its result `coarsest` (its deformed vertices).
    /// Once cancelled, the last result reached is carried up to the input's resolution.
    /// `clock` times the levels' stages (MatchResult::stage_times).
    [[nodiscard]] FinerMatch match(const Eigen::MatrixX3d& coarsest, StageClock& clock);

private:
    [[nodiscard]] TriangleMesh carry_to(int l, const Eigen::MatrixX3d& coarse_deformed) const;
    [[nodiscard]] std::vector<Eigen::Index> coarsest_rows(int l) const;
    [[nodiscard]] const AnalysedShapes* analysed_level(int l);
    [[nodiscard]] FlowResult refine(int l, const TriangleMesh& moved);
    void turn_back(int l, const TriangleMesh& rest, FlowResult& flow, const VertexMap& map);
    void fit_to_map(int l, const FineSpectrum& spectrum, FlowResult& flow,
                    std::vector<VertexMap> maps);
    bool exchange_limbs(int l, FlowResult& flow);
    void refine_further(int l, FlowResult& flow);
    [[nodiscard]] bool fits() const {
        return options_.map_fit.enabled && options_.map_fit.max_fits > 0;
    }
    [[nodiscard]] const Level& level(int l) const { return pyramid_[static_cast<std::size_t>(l)]; }

    const std::vector<Level>& pyramid_;
    const LevelFlows& flows_;
    const SpectralDescriptors* spectral_;
    const MatchOptions& options_;
    double diagonal_;
    const std::atomic<bool>& cancelled_;
    const Similarity& start_;
    double stretch_weight_;
    Eigen::MatrixX3d coarsest_deformed_;
    std::optional<AnalysedShapes> level_shapes_;  // of level analysed_, once asked for
    int analysed_ = -1;
    FinerMatch match_;
};

}  // namespace genflow::detail
