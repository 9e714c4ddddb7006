// The change-point detector (harness/history/edivisive.h) and its t test
// against hand-made series: a clean step at the right index with the right
// change, no point in flat noise at the default alpha, two steps, a step
// under --min-change left out, and the same answer every time.
#include "history/edivisive.h"
#include "history/series.h"
#include "history/t_test.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace {

using namespace cavity::history;

// Normal noise from a fixed generator (splitmix64 and Box-Muller): the
// standard library's distributions may differ between library versions.
struct Gauss {
    uint64_t state;
    double uniform() {
        uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return (double((z ^ (z >> 31)) >> 11) + 0.5) / 9007199254740992.0;
    }
    double next() { return std::sqrt(-2 * std::log(uniform())) * std::cos(6.283185307179586 * uniform()); }
};

// `levels[i]` for `lengths[i]` points each, times (1 + cv * noise).
std::vector<double> series(const std::vector<double>& levels, const std::vector<size_t>& lengths, double cv, uint64_t seed) {
    Gauss g{seed};
    std::vector<double> out;
    for (size_t i = 0; i < levels.size(); ++i)
        for (size_t j = 0; j < lengths[i]; ++j) out.push_back(levels[i] * (1 + cv * g.next()));
    return out;
}

TEST(HistoryTTest, MatchesStudentsDistribution) {
    // scipy.stats.t.sf(2.0, 10) * 2 = 0.073388; for df = 3 the closed form
    // 1 - (2 / pi) (atan(u) + u / (1 + u^2)), u = t / sqrt(3): 0.028008456 at t = 4.
    EXPECT_NEAR(twoSidedP(2.0, 10), 0.0733880, 1e-6);
    EXPECT_NEAR(twoSidedP(-4.0, 3), 0.0280084560, 1e-8);
    EXPECT_NEAR(twoSidedP(0.0, 7), 1.0, 1e-12);
    const double a[] = {1, 2, 3, 4}, b[] = {3, 4, 5, 6};
    const TTest t = studentT(a, 4, b, 4);   // scipy.stats.ttest_ind: t = 2.19089, p = 0.070988
    EXPECT_NEAR(t.t, 2.190890, 1e-5);
    EXPECT_NEAR(t.p, 0.070988, 1e-5);
    EXPECT_EQ(t.df, 6);
}

TEST(HistoryDetector, CleanStepAtTheRightIndexWithTheRightChange) {
    const auto x = series({1.0, 1.10}, {15, 15}, 0.01, 1);
    const auto cps = detectChangePoints(x);
    ASSERT_EQ(cps.size(), 1u);
    EXPECT_EQ(cps[0].index, 15u);
    EXPECT_NEAR(cps[0].change(), 0.10, 0.01);
    EXPECT_LT(cps[0].pValue, 1e-6);
}

TEST(HistoryDetector, FlatNoisySeriesGivesNoneAtTheDefaults) {
    size_t found = 0;
    for (uint64_t seed = 1; seed <= 40; ++seed) found += detectChangePoints(series({1.0}, {40}, 0.01, seed)).size();
    EXPECT_EQ(found, 0u);
    // min-change off: only alpha guards; at 0.001 flat noise still gives (almost) none.
    DetectorOptions noMin;
    noMin.minChange = 0;
    size_t alphaOnly = 0;
    for (uint64_t seed = 1; seed <= 40; ++seed) alphaOnly += detectChangePoints(series({1.0}, {40}, 0.01, seed), noMin).size();
    EXPECT_LE(alphaOnly, 2u) << "false alarms in 40 flat series at alpha 0.001";
}

TEST(HistoryDetector, TwoStepsAreBothFound) {
    const auto x = series({1.0, 1.2, 0.9}, {12, 12, 12}, 0.01, 7);
    const auto cps = detectChangePoints(x);
    ASSERT_EQ(cps.size(), 2u);
    EXPECT_EQ(cps[0].index, 12u);
    EXPECT_EQ(cps[1].index, 24u);
    EXPECT_NEAR(cps[0].change(), 0.20, 0.02);
    EXPECT_NEAR(cps[1].change(), 0.9 / 1.2 - 1, 0.02);
}

TEST(HistoryDetector, StepsAcrossWindowsAreFound) {
    // 120 points, window 50: the steps lie in different windows.
    const auto x = series({1.0, 1.15, 1.0}, {45, 40, 35}, 0.01, 11);
    const auto cps = detectChangePoints(x);
    ASSERT_EQ(cps.size(), 2u);
    EXPECT_EQ(cps[0].index, 45u);
    EXPECT_EQ(cps[1].index, 85u);
}

TEST(HistoryDetector, ChangeUnderMinChangeIsNotReported) {
    const auto x = series({1.0, 1.015}, {20, 20}, 0.001, 3);
    DetectorOptions one;
    one.minChange = 0.01;
    const auto seen = detectChangePoints(x, one);
    ASSERT_EQ(seen.size(), 1u) << "a 1.5% step in 0.1% noise is significant";
    EXPECT_EQ(seen[0].index, 20u);
    EXPECT_TRUE(detectChangePoints(x).empty()) << "under the default --min-change 2%";
}

TEST(HistoryDetector, SameInputSameOutput) {
    const auto x = series({1.0, 1.3, 1.1, 1.25}, {9, 14, 11, 10}, 0.03, 5);
    const auto a = detectChangePoints(x), b = detectChangePoints(x);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].index, b[i].index);
        EXPECT_EQ(a[i].pValue, b[i].pValue);
    }
}

TEST(HistoryDetector, TooShortOrConstantSeries) {
    EXPECT_TRUE(detectChangePoints({}).empty());
    EXPECT_TRUE(detectChangePoints({1.0, 2.0}).empty());
    EXPECT_TRUE(detectChangePoints(std::vector<double>(30, 1.0)).empty());
    // Without noise a step is certain: p = 0.
    std::vector<double> step(10, 1.0);
    step.resize(20, 2.0);
    const auto cps = detectChangePoints(step);
    ASSERT_EQ(cps.size(), 1u);
    EXPECT_EQ(cps[0].index, 10u);
    EXPECT_EQ(cps[0].pValue, 0.0);
}

TEST(HistoryDetector, EnergySplitPicksTheStep) {
    const std::vector<double> x = {1, 1, 1, 1, 5, 5, 5};
    EXPECT_EQ(bestSplit(x, 0, x.size()).index, 4u);
    EXPECT_EQ(bestSplit(x, 0, 1).index, 1u);   // nothing to split
}

TEST(HistoryMedianInterval, OrderStatistics) {
    std::vector<double> x;
    for (int i = 1; i <= 10; ++i) x.push_back(i);
    double lo = 0, hi = 0;
    bool less = true;
    // Binomial(10, 1/2): P(B <= 1) = 0.0107 <= 0.025 < P(B <= 2): [x_2, x_9].
    medianInterval(x, lo, hi, less);
    EXPECT_FALSE(less);
    EXPECT_EQ(lo, 2);
    EXPECT_EQ(hi, 9);
    medianInterval({1, 2, 3, 4, 5}, lo, hi, less);
    EXPECT_TRUE(less);
    EXPECT_EQ(lo, 1);
    EXPECT_EQ(hi, 5);
}

}  // namespace
