// SPDX-License-Identifier: MIT
#include "matching/analysis_store.h"

#include <cstddef>
#include <cstring>
#include <span>

namespace genflow {

TemplateCache::TemplateCache() : store_(std::make_unique<detail::AnalysisStore>()) {}

TemplateCache::~TemplateCache() = default;

std::size_t TemplateCache::size() const {
    return store_->size();
}

namespace detail {

namespace {

// FNV-1a over `bytes`, continuing from `hash`.
std::uint64_t fnv1a(std::uint64_t hash, std::span<const std::byte> bytes) {
    constexpr std::uint64_t kPrime = 0x100000001b3ULL;
    for (const std::byte byte : bytes) {
        hash = (hash ^ std::to_integer<std::uint64_t>(byte)) * kPrime;
    }
    return hash;
}

template <class Matrix>
std::uint64_t hash_matrix(std::uint64_t hash, const Matrix& matrix) {
    const Eigen::Index rows = matrix.rows();
    hash = fnv1a(hash, std::as_bytes(std::span(&rows, 1)));
    return fnv1a(hash,
                 std::as_bytes(std::span(matrix.data(), static_cast<std::size_t>(matrix.size()))));
}

// Bit for bit: a NaN equals itself, 0.0 does not equal -0.0, as an analysis would tell them.
template <class Matrix>
bool same_bytes(const Matrix& a, const Matrix& b) {
    return a.rows() == b.rows() &&
           std::memcmp(a.data(), b.data(),
                       static_cast<std::size_t>(a.size()) * sizeof(*a.data())) == 0;
}

bool same_mesh(const TriangleMesh& a, const TriangleMesh& b) {
    return same_bytes(a.V, b.V) && same_bytes(a.F, b.F);
}

}  // namespace

AnalysisStore::Key AnalysisStore::key_of(std::string_view kind, const TriangleMesh& mesh,
                                         Eigen::Index parameter) {
    constexpr std::uint64_t kOffsetBasis = 0xcbf29ce484222325ULL;
    return {kind, parameter, hash_matrix(hash_matrix(kOffsetBasis, mesh.V), mesh.F)};
}

const AnalysisStore::Entry* AnalysisStore::entry(const Key& key, const TriangleMesh& mesh) const {
    for (const Entry& kept : entries_) {
        if (kept.key.hash == key.hash && kept.key.parameter == key.parameter &&
            kept.key.kind == key.kind && same_mesh(*kept.mesh, mesh)) {
            return &kept;
        }
    }
    return nullptr;
}

std::shared_ptr<const void> AnalysisStore::find(const Key& key, const TriangleMesh& mesh) const {
    const std::scoped_lock lock(mutex_);
    const Entry* kept = entry(key, mesh);
    return kept != nullptr ? kept->value : nullptr;
}

std::shared_ptr<const void> AnalysisStore::keep(const Key& key, const TriangleMesh& mesh,
                                                std::shared_ptr<const void> value) {
    const std::scoped_lock lock(mutex_);
    if (const Entry* kept = entry(key, mesh)) {
        return kept->value;
    }
    // One copy of each mesh, however many analyses of it are kept.
    std::shared_ptr<const TriangleMesh> copy;
    for (const Entry& kept : entries_) {
        if (kept.key.hash == key.hash && same_mesh(*kept.mesh, mesh)) {
            copy = kept.mesh;
            break;
        }
    }
    if (!copy) {
        copy = std::make_shared<const TriangleMesh>(mesh);
    }
    entries_.push_back({key, std::move(copy), value});
    return value;
}

std::size_t AnalysisStore::size() const {
    const std::scoped_lock lock(mutex_);
    return entries_.size();
}

}  // namespace detail

}  // namespace genflow
