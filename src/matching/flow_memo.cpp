// SPDX-License-Identifier: MIT
#include "matching/flow_memo.h"

#include <algorithm>

namespace genflow::detail {

namespace {

// Equal to the bit (NaN never occurs in a request that flows). Two different starts differ in
// their first entries, so the comparison of a request that misses ends there.
template <class Matrix>
bool same(const Matrix& a, const Matrix& b) {
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           std::equal(a.data(), a.data() + a.size(), b.data());
}

}  // namespace

bool FlowMemo::Entry::answers(const FlowRequest& request) const {
    return level == request.level && iterations == request.iterations && prior == request.prior &&
           stretch_weight == request.stretch_weight &&
           placement.scale == request.placement->scale && same(start, *request.start) &&
           same(placement.rotation, request.placement->rotation) &&
           same(placement.translation, request.placement->translation) &&
           same(descriptors.moving, request.descriptors->moving) &&
           same(descriptors.fixed, request.descriptors->fixed);
}

const FlowMemo::Entry* FlowMemo::entry_for(const FlowRequest& request) const {
    const auto found = std::find_if(entries_.begin(), entries_.end(),
                                    [&](const Entry& entry) { return entry.answers(request); });
    return found == entries_.end() ? nullptr : &*found;
}

std::optional<FlowResult> FlowMemo::find(const FlowRequest& request) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    const Entry* entry = entry_for(request);
    if (entry == nullptr) {
        return std::nullopt;
    }
    ++reused_;
    return entry->result;
}

void FlowMemo::keep(const FlowRequest& request, const FlowResult& result) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (entry_for(request) == nullptr) {
        entries_.push_back({request.level, *request.start, request.iterations, *request.placement,
                            request.prior, *request.descriptors, request.stretch_weight, result});
    }
}

int FlowMemo::reused() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return reused_;
}

}  // namespace genflow::detail
