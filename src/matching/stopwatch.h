// SPDX-License-Identifier: MIT
// The matcher's stages report how long they took (MatchResult, MatchLevel).
#pragma once

#include <algorithm>
#include <chrono>
#include <ctime>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "genflow/matching/match.h"

namespace genflow::detail {

/// Seconds from `t` to now, on the steady clock.
[[nodiscard]] inline double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// The stages of one match timed one after another (MatchResult::stage_times): end() closes
/// the stage that began where the previous one ended (or at construction), and a stage ended
/// twice adds up. Wall time and the process's processor time side by side: on a shared machine
/// only the second measures the stage.
class StageClock {
public:
    StageClock() : wall_(std::chrono::steady_clock::now()), processor_(std::clock()) {}

    /// The stages ended from now on are named `prefix` + their name: a second reading's stages
    /// apart from the first's.
    void name_from_now(std::string prefix) { prefix_ = std::move(prefix); }

    void end(std::string_view stage) {
        const auto wall = std::chrono::steady_clock::now();
        const std::clock_t processor = std::clock();
        const std::string name = prefix_ + std::string(stage);
        auto it = find(times_, name);
        if (it == times_.end()) {
            it = times_.insert(times_.end(), MatchStageTime{.stage = name});
        }
        it->seconds += std::chrono::duration<double>(wall - wall_).count();
        it->processor_seconds += static_cast<double>(processor - processor_) / CLOCKS_PER_SEC;
        wall_ = wall;
        processor_ = processor;
    }

    [[nodiscard]] const std::vector<MatchStageTime>& times() const { return times_; }

    /// The wall seconds of the stage named `stage` in full (its prefix included), 0 before it
    /// ends: what the results that report a stage's time apart read.
    [[nodiscard]] double seconds(std::string_view stage) const {
        const auto it = find(times_, stage);
        return it == times_.end() ? 0 : it->seconds;
    }

private:
    // The stage named `stage` in `times` (const or not), or its end.
    template <typename Times>
    static auto find(Times& times, std::string_view stage) -> decltype(times.begin()) {
        return std::find_if(times.begin(), times.end(),
                            [&](const MatchStageTime& t) { return t.stage == stage; });
    }

    std::chrono::steady_clock::time_point wall_;
    std::clock_t processor_;
    std::string prefix_;
    std::vector<MatchStageTime> times_;
};

}  // namespace genflow::detail
