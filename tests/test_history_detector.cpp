// The change-point detector (harness/history/edivisive.h) and its t test
// against hand-made series: a clean step at the right index with the right
// change, no point in flat noise at the default alpha, two steps, a step
// under --min-change left out, a regression reverted a few commits later,
// two small steps in a row, the newest commits held to more evidence, and
// the same answer every time.
#include "history/edivisive.h"
#include "history/series.h"
#include "history/t_test.h"

#include "history_synthetic.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace {

using namespace cavity::history;

using cavity::synthetic::series;
using cavity::synthetic::stepped;

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
    DetectorOptions two;
    two.minChange = 0.02;
    EXPECT_TRUE(detectChangePoints(x, two).empty()) << "under --min-change 2%";
}

// A regression that lasted three commits and was then fixed, early in the
// series: the rest of the series must not dilute it.
TEST(HistoryDetector, RevertedRegressionIsFoundWithItsRevert) {
    for (uint64_t seed = 1; seed <= 20; ++seed) {
        const auto x = stepped(30, 8, 0.05, 0.003, seed, 11);
        const auto cps = detectChangePoints(x);
        ASSERT_EQ(cps.size(), 2u) << "seed " << seed;
        EXPECT_EQ(cps[0].index, 8u);
        EXPECT_NEAR(cps[0].change(), 0.05, 0.01);
        EXPECT_EQ(cps[1].index, 11u);
        EXPECT_LT(cps[1].change(), 0);
    }
    // At the noisier level too, most of the time.
    int found = 0;
    for (uint64_t seed = 1; seed <= 40; ++seed)
        for (const auto& c : detectChangePoints(stepped(30, 10, 0.05, 0.01, seed, 13))) found += c.index == 10 && c.change() > 0;
    EXPECT_GE(found, 36) << "of 40";
}

// Two small steps ten commits apart: each named at its own commit, not one
// step of both at the second.
TEST(HistoryDetector, TwoSmallStepsInARowAreEachNamed) {
    for (uint64_t seed = 1; seed <= 20; ++seed) {
        auto x = stepped(30, 8, 0.015, 0.003, seed);
        for (size_t i = 18; i < x.size(); ++i) x[i] *= 1.015;
        const auto cps = detectChangePoints(x);
        ASSERT_EQ(cps.size(), 2u) << "seed " << seed;
        EXPECT_EQ(cps[0].index, 8u);
        EXPECT_EQ(cps[1].index, 18u);
        EXPECT_NEAR(cps[0].change(), 0.015, 0.004);
        EXPECT_NEAR(cps[1].change(), 0.015, 0.004);
    }
}

// A step at the last commit is found when it is clear, and marked
// provisional; a weaker one waits for more commits.
TEST(HistoryDetector, NewestCommitsNeedMoreEvidence) {
    const auto clear = detectChangePoints(stepped(30, 29, 0.05, 0.003, 3));
    ASSERT_EQ(clear.size(), 1u);
    EXPECT_EQ(clear[0].index, 29u);
    EXPECT_TRUE(clear[0].provisional);
    EXPECT_EQ(clear[0].pointsAfter, 1u);
    // In more noise, a smaller step is clear with four commits after it, not with one.
    int oneAfter = 0, fourAfter = 0;
    for (uint64_t seed = 1; seed <= 40; ++seed) {
        oneAfter += !detectChangePoints(stepped(30, 29, 0.04, 0.01, seed)).empty();
        for (const auto& c : detectChangePoints(stepped(30, 26, 0.04, 0.01, seed))) fourAfter += c.index == 26 && !c.provisional;
    }
    EXPECT_LE(oneAfter, 12) << "of 40 alerts on one commit";
    EXPECT_GE(fourAfter, 30) << "of 40 found with four after";
}

// The splits near the ends of a flat series are the most extreme by chance;
// judged as the maximum they are, they raise no alarm.
TEST(HistoryDetector, FlatSeriesAtOnePercentNoiseRaiseAlmostNone) {
    int alerts = 0;
    for (uint64_t seed = 1; seed <= 400; ++seed) alerts += !detectChangePoints(stepped(30, 0, 0, 0.01, seed * 104729)).empty();
    EXPECT_LE(alerts, 2) << "of 400 flat series";
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
    EXPECT_EQ(bestSplit(x, 0, x.size()).end, x.size());
    const std::vector<double> excursion = {1, 1, 1, 1, 5, 5, 1, 1, 1, 1};
    EXPECT_EQ(bestSplit(excursion, 0, excursion.size()).index, 4u);
    EXPECT_EQ(bestSplit(excursion, 0, excursion.size()).end, 6u);
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
