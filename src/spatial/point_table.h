// SPDX-License-Identifier: MIT
// A hash table from 3D points (compared bit for bit) to 32-bit numbers.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace genflow::detail {

// Points to numbers by open addressing (linear probing in one array): a lookup is about one
// cache miss, where a node-based map takes several.
class PointTable {
public:
    static constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();

    // The value stored for p, or `value` after storing it; and whether it was stored now.
    std::pair<std::uint32_t, bool> find_or_insert(const Eigen::Vector3d& p, std::uint32_t value) {
        if (2 * (size_ + 1) > values_.size()) {
            grow();
        }
        const std::size_t mask = values_.size() - 1;
        std::size_t at = hash(p) & mask;
        while (values_[at] != kEmpty) {
            if (keys_[at] == p) {
                return {values_[at], false};
            }
            at = (at + 1) & mask;
        }
        keys_[at] = p;
        values_[at] = value;
        ++size_;
        return {value, true};
    }

private:
    static std::size_t hash(const Eigen::Vector3d& p) {
        const std::hash<double> h;  // equal for +0 and −0, as == is
        std::size_t x = h(p[0]);
        x = (x ^ h(p[1])) * 0x9e3779b97f4a7c15ULL;
        x = (x ^ h(p[2])) * 0xc2b2ae3d27d4eb4fULL;
        return x ^ (x >> 29);
    }

    void grow() {
        std::vector<Eigen::Vector3d> keys = std::move(keys_);
        std::vector<std::uint32_t> values = std::move(values_);
        const std::size_t capacity = std::max<std::size_t>(1024, 2 * values.size());
        keys_.assign(capacity, Eigen::Vector3d::Zero());
        values_.assign(capacity, kEmpty);
        size_ = 0;
        for (std::size_t k = 0; k < values.size(); ++k) {
            if (values[k] != kEmpty) {
                find_or_insert(keys[k], values[k]);
            }
        }
    }

    std::vector<Eigen::Vector3d> keys_;
    std::vector<std::uint32_t> values_;
    std::size_t size_ = 0;
};

}  // namespace genflow::detail
