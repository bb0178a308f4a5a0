// SPDX-License-Identifier: MIT
#include "genflow/evaluation/benchmark_pairs.h"

#include <algorithm>
#include <random>

#include "genflow/exceptions.h"

namespace genflow {

namespace {

// A uniform draw from [0, bound), by rejection of the generator's last incomplete range.
std::size_t uniform_below(std::mt19937_64& generator, std::size_t bound) {
    const std::uint64_t range = std::mt19937_64::max();
    const std::uint64_t limit = range - range % bound;
    std::uint64_t draw = generator();
    while (draw >= limit) {
        draw = generator();
    }
    return static_cast<std::size_t>(draw % bound);
}

// The first `count` of `pairs` after a partial Fisher–Yates shuffle.
std::vector<ShapePair> drawn(std::vector<ShapePair> pairs, std::size_t count,
                             std::mt19937_64& generator) {
    count = std::min(count, pairs.size());
    for (std::size_t i = 0; i < count; ++i) {
        std::swap(pairs[i], pairs[i + uniform_below(generator, pairs.size() - i)]);
    }
    pairs.resize(count);
    return pairs;
}

}  // namespace

std::vector<ShapePair> benchmark_pairs(const std::vector<int>& subjects,
                                       std::optional<std::size_t> count, std::uint64_t seed) {
    if (subjects.size() < 2) {
        throw InvalidInput("benchmark_pairs: a benchmark needs at least two shapes");
    }
    std::vector<ShapePair> within;
    std::vector<ShapePair> across;
    const auto n = static_cast<Eigen::Index>(subjects.size());
    for (Eigen::Index from = 0; from < n; ++from) {
        for (Eigen::Index to = 0; to < n; ++to) {
            if (from != to) {
                const bool same = subjects[static_cast<std::size_t>(from)] ==
                                  subjects[static_cast<std::size_t>(to)];
                (same ? within : across).push_back({from, to, same});
            }
        }
    }
    std::vector<ShapePair> pairs;
    if (!count) {
        pairs = within;
        pairs.insert(pairs.end(), across.begin(), across.end());
    } else {
        std::mt19937_64 generator(seed);
        std::size_t want_within = std::min(within.size(), (*count + 1) / 2);
        const std::size_t want_across = std::min(across.size(), *count - want_within);
        want_within = std::min(within.size(), *count - want_across);
        pairs = drawn(std::move(within), want_within, generator);
        const std::vector<ShapePair> other = drawn(std::move(across), want_across, generator);
        pairs.insert(pairs.end(), other.begin(), other.end());
    }
    std::sort(pairs.begin(), pairs.end(), [](const ShapePair& a, const ShapePair& b) {
        return a.from != b.from ? a.from < b.from : a.to < b.to;
    });
    return pairs;
}

}  // namespace genflow
