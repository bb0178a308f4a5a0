// SPDX-License-Identifier: MIT
#pragma once

#include <cstddef>
#include <memory>

namespace genflow {

namespace detail {
class AnalysisStore;
}  // namespace detail

/// What match() computes of a template alone, kept for the next match of the same template
/// (MatchOptions::template_cache): its repair, its coarser levels and their embeddings, the heat
/// kernel signatures and eigenbasis of its coarsest level, the intrinsic analyses of its coarse
/// levels and the eigenbasis of the whole template. A batch of targets against one template
/// prepares the template once.
///
/// Each analysis is kept with the mesh it was computed from and found again only for a mesh
/// equal to it, bit for bit: a match gives the same result with a cache as without one, whatever
/// the cache holds. It keeps everything it is given, so one cache serves one template. Safe to
/// share between threads; not copyable (share it through a std::shared_ptr).
class TemplateCache {
public:
    TemplateCache();
    ~TemplateCache();
    TemplateCache(const TemplateCache&) = delete;
    TemplateCache& operator=(const TemplateCache&) = delete;

    /// How many analyses it holds.
    [[nodiscard]] std::size_t size() const;

    /// Where match()'s stages keep and find the analyses (src/matching/analysis_store.h).
    [[nodiscard]] detail::AnalysisStore& store() const { return *store_; }

private:
    std::unique_ptr<detail::AnalysisStore> store_;
};

}  // namespace genflow
