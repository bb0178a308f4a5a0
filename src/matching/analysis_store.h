// SPDX-License-Identifier: MIT
// The analyses of meshes that match() computes more than once, kept by TemplateCache: each with
// the mesh it was computed from, found again only for an equal mesh. An analysis is a function
// of its mesh and one parameter alone, so a kept one is what computing it again would give.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <vector>

#include "genflow/matching/template_cache.h"
#include "genflow/mesh.h"
#include "matching/side_by_side.h"

namespace genflow::detail {

class AnalysisStore {
public:
    /// The analysis `kind` with `parameter` of `mesh`: the kept one, or `compute()`, kept.
    /// Where two threads compute the same analysis at once, both get the one kept first.
    template <class T, class Compute>
    [[nodiscard]] std::shared_ptr<const T> get(std::string_view kind, const TriangleMesh& mesh,
                                               Eigen::Index parameter, Compute compute) {
        const Key key = key_of(kind, mesh, parameter);
        if (std::shared_ptr<const void> kept = find(key, mesh)) {
            return std::static_pointer_cast<const T>(kept);
        }
        std::shared_ptr<const void> computed = std::make_shared<const T>(compute());
        return std::static_pointer_cast<const T>(keep(key, mesh, std::move(computed)));
    }

    /// How many analyses are kept.
    [[nodiscard]] std::size_t size() const;

private:
    struct Key {
        std::string_view kind;  // a literal at every call site
        Eigen::Index parameter = 0;
        std::uint64_t hash = 0;  // of the mesh's sizes and bytes
    };
    struct Entry {
        Key key;
        std::shared_ptr<const TriangleMesh> mesh;  // shared by the entries of equal meshes
        std::shared_ptr<const void> value;
    };

    [[nodiscard]] static Key key_of(std::string_view kind, const TriangleMesh& mesh,
                                    Eigen::Index parameter);
    [[nodiscard]] std::shared_ptr<const void> find(const Key& key, const TriangleMesh& mesh) const;
    std::shared_ptr<const void> keep(const Key& key, const TriangleMesh& mesh,
                                     std::shared_ptr<const void> value);
    // The entry for `key` and `mesh`, if there is one (the mutex held).
    [[nodiscard]] const Entry* entry(const Key& key, const TriangleMesh& mesh) const;

    mutable std::mutex mutex_;
    std::vector<Entry> entries_;
};

/// The analysis through `cache` (MatchOptions::template_cache), or computed for this call alone
/// where there is none.
template <class T, class Compute>
[[nodiscard]] std::shared_ptr<const T> cached(const std::shared_ptr<TemplateCache>& cache,
                                              std::string_view kind, const TriangleMesh& mesh,
                                              Eigen::Index parameter, Compute compute) {
    if (cache) {
        return cache->store().get<T>(kind, mesh, parameter, compute);
    }
    return std::make_shared<const T>(compute());
}

/// A template's analysis and a target's, as analysed_side_by_side() finds them.
template <class T>
struct TwoAnalyses {
    std::shared_ptr<const T> of_template;  ///< through the cache, where there is one
    T of_target;
};

/// `analyse(template_mesh)` through `cache` (cached()) and `analyse(target)`, side by side: the
/// two are independent, so each is found on a thread of its own. The first exception either
/// threw is rethrown once both have ended.
template <class T, class Analyse>
[[nodiscard]] TwoAnalyses<T> analysed_side_by_side(const std::shared_ptr<TemplateCache>& cache,
                                                   std::string_view kind,
                                                   const TriangleMesh& template_mesh,
                                                   const TriangleMesh& target,
                                                   Eigen::Index parameter, Analyse analyse) {
    std::shared_ptr<const T> of_template;
    std::optional<T> of_target;
    run_side_by_side(2, [&](std::size_t k) {
        if (k == 0) {
            of_template = cached<T>(cache, kind, template_mesh, parameter,
                                    [&] { return analyse(template_mesh); });
        } else {
            of_target = analyse(target);
        }
    });
    return {std::move(of_template), std::move(*of_target)};
}

}  // namespace genflow::detail
