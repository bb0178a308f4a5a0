// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

namespace genflow {

/// An ordered pair of a benchmark's shapes: the map goes from `from` (the template) to `to`.
struct ShapePair {
    Eigen::Index from = 0;
    Eigen::Index to = 0;
    bool within_subject = false;  ///< both shapes show the same subject (a pose change only)

    friend bool operator==(const ShapePair&, const ShapePair&) = default;
};

/// The pairs of a benchmark whose shapes show the subjects `subjects[s]` (any labels): every
/// ordered pair of distinct shapes when `count` is empty, else `count` of them drawn without
/// repetition by a generator seeded with `seed`, half within a subject and half across (the
/// other kind makes up what one lacks). Sorted by `from`, then `to`. The draw is the same on
/// every platform and standard library (std::mt19937_64, with our own reduction to a range:
/// std::uniform_int_distribution is not specified exactly), so a seed names a sample.
/// \throws InvalidInput if there are fewer than two shapes.
[[nodiscard]] std::vector<ShapePair> benchmark_pairs(const std::vector<int>& subjects,
                                                     std::optional<std::size_t> count,
                                                     std::uint64_t seed);

}  // namespace genflow
