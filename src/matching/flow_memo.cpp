// SPDX-License-Identifier: MIT
#include "matching/flow_memo.h"

#include <algorithm>
#include <cstring>

namespace genflow::detail {

namespace {

// FNV-1a over the bytes of `values`: a quick filter before the exact comparison.
class Fingerprint {
public:
    template <class T>
    void add(const T* values, std::size_t count) {
        const auto* bytes = reinterpret_cast<const unsigned char*>(values);
        for (std::size_t i = 0; i < count * sizeof(T); ++i) {
            value_ = (value_ ^ bytes[i]) * kPrime;
        }
    }

    template <class Matrix>
    void add_matrix(const Matrix& matrix) {
        add(matrix.data(), static_cast<std::size_t>(matrix.size()));
    }

    [[nodiscard]] std::uint64_t value() const { return value_; }

private:
    static constexpr std::uint64_t kPrime = 1099511628211ULL;
    std::uint64_t value_ = 14695981039346656037ULL;
};

std::uint64_t fingerprint(const FlowRequest& request) {
    Fingerprint print;
    print.add(&request.level, 1);
    print.add(&request.iterations, 1);
    print.add(&request.prior, 1);
    print.add(&request.stretch_weight, 1);
    print.add_matrix(*request.start);
    print.add_matrix(request.descriptors->moving);
    return print.value();
}

// Equal to the bit (NaN never occurs in a request that flows).
template <class Matrix>
bool same(const Matrix& a, const Matrix& b) {
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           std::equal(a.data(), a.data() + a.size(), b.data());
}

}  // namespace

bool FlowMemo::Entry::answers(std::uint64_t print, const FlowRequest& request) const {
    return fingerprint == print && level == request.level && iterations == request.iterations &&
           prior == request.prior && stretch_weight == request.stretch_weight &&
           same(start, *request.start) && same(placement.rotation, request.placement->rotation) &&
           same(placement.translation, request.placement->translation) &&
           placement.scale == request.placement->scale &&
           same(descriptors.moving, request.descriptors->moving) &&
           same(descriptors.fixed, request.descriptors->fixed);
}

std::optional<FlowResult> FlowMemo::find(const FlowRequest& request) const {
    const std::uint64_t print = fingerprint(request);
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const Entry& entry : entries_) {
        if (entry.answers(print, request)) {
            ++reused_;
            return entry.result;
        }
    }
    return std::nullopt;
}

void FlowMemo::keep(const FlowRequest& request, const FlowResult& result) {
    const std::uint64_t print = fingerprint(request);
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const Entry& entry : entries_) {
        if (entry.answers(print, request)) {
            return;
        }
    }
    entries_.push_back({print, request.level, *request.start, request.iterations,
                        *request.placement, request.prior, *request.descriptors,
                        request.stretch_weight, result});
}

int FlowMemo::reused() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return reused_;
}

}  // namespace genflow::detail
