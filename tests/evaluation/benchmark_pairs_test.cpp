// SPDX-License-Identifier: MIT
#include "genflow/evaluation/benchmark_pairs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>

#include "genflow/exceptions.h"

namespace genflow {
namespace {}  // namespace

// For readable failures.
void PrintTo(const ShapePair& pair, std::ostream* out) {
    *out << pair.from << "->" << pair.to << (pair.within_subject ? " within" : " across");
}

namespace {

// Eight subjects of ten shapes, as FAUST_r's training split.
std::vector<int> faust_like_subjects() {
    std::vector<int> subjects;
    for (int s = 0; s < 80; ++s) {
        subjects.push_back(s / 10);
    }
    return subjects;
}

TEST(BenchmarkPairs, AllAreEveryOrderedPairOfDistinctShapes) {
    const std::vector<ShapePair> pairs = benchmark_pairs({0, 0, 1}, std::nullopt, 1);
    const std::vector<ShapePair> expected{{0, 1, true},  {0, 2, false}, {1, 0, true},
                                          {1, 2, false}, {2, 0, false}, {2, 1, false}};
    EXPECT_EQ(pairs, expected);
}

TEST(BenchmarkPairs, ASampleIsHalfWithinSubjectsWithoutRepeats) {
    const std::vector<int> subjects = faust_like_subjects();
    const std::vector<ShapePair> pairs = benchmark_pairs(subjects, 100, 1);
    ASSERT_EQ(pairs.size(), 100u);
    std::set<std::pair<Eigen::Index, Eigen::Index>> seen;
    int within = 0;
    for (const ShapePair& pair : pairs) {
        EXPECT_NE(pair.from, pair.to);
        EXPECT_EQ(pair.within_subject, subjects[static_cast<std::size_t>(pair.from)] ==
                                           subjects[static_cast<std::size_t>(pair.to)]);
        within += pair.within_subject ? 1 : 0;
        EXPECT_TRUE(seen.emplace(pair.from, pair.to).second);
    }
    EXPECT_EQ(within, 50);
    EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) {
        return a.from != b.from ? a.from < b.from : a.to < b.to;
    }));
}

// A seed names a sample on every platform: the draw does not go through
// std::uniform_int_distribution, whose mapping each standard library chooses.
TEST(BenchmarkPairs, ASeedNamesOneSample) {
    const std::vector<int> subjects = faust_like_subjects();
    EXPECT_EQ(benchmark_pairs(subjects, 100, 1), benchmark_pairs(subjects, 100, 1));
    EXPECT_NE(benchmark_pairs(subjects, 100, 1), benchmark_pairs(subjects, 100, 2));
    const std::vector<ShapePair> sample = benchmark_pairs(subjects, 4, 1);
    const std::vector<ShapePair> expected{
        {21, 70, false}, {27, 25, true}, {29, 26, true}, {67, 59, false}};
    EXPECT_EQ(sample, expected);
}

TEST(BenchmarkPairs, OneKindMakesUpWhatTheOtherLacks) {
    // One subject: every pair is within it.
    const std::vector<ShapePair> pairs = benchmark_pairs({0, 0, 0, 0}, 10, 5);
    EXPECT_EQ(pairs.size(), 10u);
    EXPECT_TRUE(std::all_of(pairs.begin(), pairs.end(),
                            [](const ShapePair& pair) { return pair.within_subject; }));
    EXPECT_EQ(benchmark_pairs({0, 0, 0}, 100, 5).size(), 6u);  // no more than there are
    EXPECT_THROW((void)benchmark_pairs({0}, 1, 1), InvalidInput);
}

}  // namespace
}  // namespace genflow
