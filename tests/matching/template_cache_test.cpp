// SPDX-License-Identifier: MIT
// TemplateCache: an analysis kept with its mesh is found again for an equal mesh only, and a match
// with a cache, cold or warm, is the match without one.
#include "genflow/matching/template_cache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <thread>

#include "genflow/exceptions.h"
#include "genflow/matching/match.h"
#include "genflow/mesh/primitives.h"
#include "matching/analysis_store.h"

namespace genflow::detail {
namespace {

TEST(AnalysisStore, ComputesAnAnalysisOncePerMeshKindAndParameter) {
    AnalysisStore store;
    const TriangleMesh mesh = make_icosphere(1);
    int computed = 0;
    const auto count = [&] { return ++computed; };
    EXPECT_EQ(*store.get<int>("count", mesh, 1, count), 1);
    const TriangleMesh copy = mesh;  // other storage, the same bits
    EXPECT_EQ(*store.get<int>("count", copy, 1, count), 1);
    EXPECT_EQ(*store.get<int>("count", mesh, 2, count), 2);  // another parameter
    EXPECT_EQ(*store.get<int>("other", mesh, 1, count), 3);  // another kind
    TriangleMesh moved = mesh;
    moved.V(4, 2) = std::nextafter(moved.V(4, 2), std::numeric_limits<double>::infinity());
    EXPECT_EQ(*store.get<int>("count", moved, 1, count), 4);  // one bit off
    TriangleMesh turned = mesh;
    std::swap(turned.F(0, 1), turned.F(0, 2));
    EXPECT_EQ(*store.get<int>("count", turned, 1, count), 5);  // one face reversed
    EXPECT_EQ(store.size(), 5U);
    EXPECT_EQ(computed, 5);
}

TEST(AnalysisStore, GivesThreadsComputingTheSameAnalysisTheOneKeptFirst) {
    AnalysisStore store;
    const TriangleMesh mesh = make_icosphere(2);
    std::atomic<int> computed = 0;
    std::shared_ptr<const int> a;
    std::shared_ptr<const int> b;
    const auto ask = [&](std::shared_ptr<const int>& result) {
        result = store.get<int>("count", mesh, 0, [&] { return ++computed; });
    };
    std::thread first(ask, std::ref(a));
    std::thread second(ask, std::ref(b));
    first.join();
    second.join();
    EXPECT_EQ(a.get(), b.get());  // the same kept value, however many computed it
    EXPECT_EQ(store.size(), 1U);
}

TEST(AnalysisStore, WithoutACacheComputesEveryTime) {
    int computed = 0;
    const TriangleMesh mesh = make_icosphere(1);
    const std::shared_ptr<TemplateCache> none;
    EXPECT_EQ(*cached<int>(none, "count", mesh, 0, [&] { return ++computed; }), 1);
    EXPECT_EQ(*cached<int>(none, "count", mesh, 0, [&] { return ++computed; }), 2);
}

// The vertex count of a mesh, as an analysis that tells the two meshes apart.
int vertex_count(const TriangleMesh& mesh) {
    return static_cast<int>(mesh.V.rows());
}

TEST(AnalysisStore, AnalysesTheTemplateThroughTheCacheAndTheTargetEveryTime) {
    const auto cache = std::make_shared<TemplateCache>();
    const TriangleMesh template_mesh = make_icosphere(1);
    const TriangleMesh target = make_icosphere(2);
    std::atomic<int> computed = 0;
    const auto analyse = [&](const TriangleMesh& mesh) {
        ++computed;
        return vertex_count(mesh);
    };
    const TwoAnalyses<int> first =
        analysed_side_by_side<int>(cache, "count", template_mesh, target, 0, analyse);
    EXPECT_EQ(*first.of_template, vertex_count(template_mesh));
    EXPECT_EQ(first.of_target, vertex_count(target));
    const TwoAnalyses<int> second =
        analysed_side_by_side<int>(cache, "count", template_mesh, target, 0, analyse);
    EXPECT_EQ(second.of_template.get(), first.of_template.get());  // the kept one
    EXPECT_EQ(second.of_target, vertex_count(target));
    EXPECT_EQ(computed, 3);  // the template once, the target each time
    EXPECT_EQ(cache->store().size(), 1U);
}

TEST(AnalysisStore, RethrowsWhatEitherSideThrewAndKeepsNothingOfAFailedTemplate) {
    const auto cache = std::make_shared<TemplateCache>();
    const TriangleMesh template_mesh = make_icosphere(1);
    const TriangleMesh target = make_icosphere(2);
    for (const Eigen::Index failing : {template_mesh.V.rows(), target.V.rows()}) {
        const auto analyse = [&](const TriangleMesh& mesh) {
            if (mesh.V.rows() == failing) {
                throw SolverError("no analysis");
            }
            return vertex_count(mesh);
        };
        EXPECT_THROW(static_cast<void>(analysed_side_by_side<int>(cache, "count", template_mesh,
                                                                  target, 0, analyse)),
                     SolverError);
    }
    EXPECT_EQ(cache->store().size(), 1U);  // the template's, from the second call
}

// A quick match of the whole pipeline on two levels: every analysis the cache keeps is asked for.
MatchOptions quick_options() {
    MatchOptions options;
    options.coarse_vertices = 150;
    options.max_iterations = 40;
    options.fine_iterations = 5;
    options.refinement_iterations = 10;
    options.starts.selection_iterations = 30;
    return options;
}

void expect_same_match(const MatchResult& a, const MatchResult& b) {
    EXPECT_EQ(a.deformed.V, b.deformed.V);
    EXPECT_EQ(a.counterparts, b.counterparts);
    EXPECT_EQ(a.hausdorff_energy, b.hausdorff_energy);
    EXPECT_EQ(a.intrinsic_disagreement, b.intrinsic_disagreement);
    ASSERT_EQ(a.levels.size(), b.levels.size());
    for (std::size_t l = 0; l < a.levels.size(); ++l) {
        EXPECT_EQ(a.levels[l].energy, b.levels[l].energy) << "level " << l;
    }
}

TEST(TemplateCache, GivesTheMatchWithoutItAndKeepsTheTemplatesAnalysesForTheNextTarget) {
    const TriangleMesh template_mesh = make_limb(3);
    TriangleMesh target = make_limb(3, 5);
    target.V = bend_at_joints(target.V, {{{1.0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 0.6, 0.4}});
    TriangleMesh other_target = make_limb(3, 7);

    const MatchResult alone = match(template_mesh, target, quick_options());
    MatchOptions options = quick_options();
    options.template_cache = std::make_shared<TemplateCache>();
    (void)match(template_mesh, other_target, options);  // fills the cache
    const std::size_t kept = options.template_cache->size();
    EXPECT_GE(kept, 5U);  // repair, a coarser level, the spectral view, shapes, eigenbasis
    expect_same_match(match(template_mesh, target, options), alone);
    EXPECT_EQ(options.template_cache->size(), kept);  // all found, none added
}

}  // namespace
}  // namespace genflow::detail
