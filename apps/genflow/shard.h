// SPDX-License-Identifier: MIT
// --shard i/N of benchmark and batch: a stable share of a list of jobs, for job arrays and
// processes sharing a machine.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace genflow::cli {

/// The items at positions p with p mod N = i: every N-th, from the i-th. The N shards together
/// take every item once, whatever the machines, and a shard's share does not change between
/// runs. An empty `shard` takes them all.
/// \throws InvalidInput "--shard: expected i/N with 0 <= i < N, got '...'".
template <typename Item>
[[nodiscard]] std::vector<Item> shard_of(const std::vector<Item>& items, const std::string& shard);

/// The parsed i and N of "i/N" (0 and 1 for an empty text).
struct Shard {
    std::size_t index = 0;
    std::size_t count = 1;
};
[[nodiscard]] Shard parse_shard(const std::string& shard);

template <typename Item>
std::vector<Item> shard_of(const std::vector<Item>& items, const std::string& shard) {
    const Shard share = parse_shard(shard);
    std::vector<Item> taken;
    for (std::size_t p = share.index; p < items.size(); p += share.count) {
        taken.push_back(items[p]);
    }
    return taken;
}

}  // namespace genflow::cli
