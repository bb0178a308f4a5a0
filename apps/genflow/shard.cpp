// SPDX-License-Identifier: MIT
#include "shard.h"

#include <charconv>
#include <string_view>

#include "genflow/exceptions.h"

namespace genflow::cli {

Shard parse_shard(const std::string& shard) {
    if (shard.empty()) {
        return {};
    }
    const auto parse = [](std::string_view text, std::size_t& value) {
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        return error == std::errc() && end == text.data() + text.size() && !text.empty();
    };
    const auto slash = shard.find('/');
    Shard share;
    if (slash == std::string::npos ||
        !parse(std::string_view(shard).substr(0, slash), share.index) ||
        !parse(std::string_view(shard).substr(slash + 1), share.count) || share.count == 0 ||
        share.index >= share.count) {
        throw InvalidInput("--shard: expected i/N with 0 <= i < N, got '" + shard + "'");
    }
    return share;
}

}  // namespace genflow::cli
