// Statistics and configuration ids: plain functions, no GPU.
#include "harness_names.h"
#include "core/config.h"
#include "pipeline/config_id.h"
#include "stats/hodges_lehmann.h"
#include "stats/mann_whitney.h"
#include "stats/stats.h"
#include "measure/timing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace cavity {

using namespace cavity::harness;
namespace {

TEST(Stats, SummarizesAKnownSample) {
    const Stats s = summarize({4, 1, 3, 2, 5});
    EXPECT_EQ(s.count, 5);
    EXPECT_DOUBLE_EQ(s.median, 3);
    EXPECT_DOUBLE_EQ(s.min, 1);
    EXPECT_DOUBLE_EQ(s.max, 5);
    EXPECT_DOUBLE_EQ(s.mean, 3);
    EXPECT_NEAR(s.p90, 4.6, 1e-12);            // rank 3.6 between 4 and 5
    EXPECT_NEAR(s.stddev, std::sqrt(2.5), 1e-12);
    EXPECT_NEAR(s.cv, std::sqrt(2.5) / 3, 1e-12);
}

TEST(ClockCheck, RejectsTimersThatMissTheWork) {
    const ClockCheck c;
    // llvmpipe GL, measured (docs/gpu.md): the timestamps of a pass bracket
    // almost none of its drained wall time.
    EXPECT_FALSE(c.trusted(0.06, 48.8));
    EXPECT_FALSE(c.trusted(0.0, 1.0));
    EXPECT_FALSE(c.trusted(10.0, 5.0));        // more GPU time than wall time
    // H100: timestamps close to the wall clock; tiny frames within the
    // fixed submission overhead.
    EXPECT_TRUE(c.trusted(0.339, 0.351));
    EXPECT_TRUE(c.trusted(0.05, 0.2));
}

TEST(ConfigId, IsTheCanonicalPath) {
    RunConfig c;
    ASSERT_TRUE(setParam(c, "scene", "slats").ok());
    ASSERT_TRUE(setParam(c, "samples", "32").ok());
    ASSERT_TRUE(setParam(c, "blur", "2").ok());
    c.half = true;
    c.api = gpu::Api::OpenGL;
    c.stage = gpu::Stage::Fragment;
    EXPECT_EQ(configId(c), "slats/alchemy/n32/b2/half/320x180/gl/fragment");
}

TEST(ConfigValidation, NamesFlagValueAndRange) {
    // Parsed: refused when the flag is read (kernels::parseValue).
    RunConfig c;
    const Status parsed = setParam(c, "samples", "300");
    ASSERT_FALSE(parsed.ok());
    EXPECT_EQ(parsed.error().code, ErrorCode::BadInput);
    EXPECT_EQ(parsed.error().message, "--samples 300: must be an integer in 1..256 (samples)");
    // Set in code: validate() checks it against the same declaration, in the same words.
    c.params["samples"] = 300;
    const Status s = validate(c);
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().code, ErrorCode::BadInput);
    EXPECT_EQ(s.error().message, "--samples 300: must be an integer in 1..256 (samples)");
}

// ---- Mann-Whitney U: p-values against scipy ----
// Each expected value is what Debian 12's scipy 1.10.1 prints for the call
// quoted beside it; its method='auto' goes exact when either sample has at
// most 8 values and nothing is tied (scipy/stats/_mannwhitneyu.py,
// _mwu_choose_method), as current scipy does.

TEST(MannWhitney, OneSmallSampleIsEnoughForTheExactP) {
    // mannwhitneyu([0.5, 1.5], [1, 2, ..., 12], alternative='two-sided') -> U = 1.0,
    // p = 0.04395604395604396 (exact: 2 * 2 / C(14, 2)); method='asymptotic' gives 0.05523425371806383.
    std::vector<double> twelve;
    for (int i = 1; i <= 12; ++i) twelve.push_back(i);
    const auto r = stats::mannWhitneyU({0.5, 1.5}, twelve);
    EXPECT_TRUE(r.exact);
    EXPECT_DOUBLE_EQ(r.u, 1.0);
    EXPECT_NEAR(r.p, 0.04395604395604396, 1e-12);
    EXPECT_NEAR(stats::mannWhitneyUAsymptotic({0.5, 1.5}, twelve).p, 0.05523425371806383, 1e-12);

    // b = [10.05 + 0.15 * i for i in range(20)]
    // mannwhitneyu([12.11, 12.51, 12.97], b, alternative='two-sided') -> U = 51.0, p = 0.05985319028797289
    // (exact; method='asymptotic' gives 0.06129168042631612).
    std::vector<double> twenty;
    for (int i = 0; i < 20; ++i) twenty.push_back(10.05 + 0.15 * i);
    const auto s = stats::mannWhitneyU({12.11, 12.51, 12.97}, twenty);
    EXPECT_TRUE(s.exact);
    EXPECT_DOUBLE_EQ(s.u, 51.0);
    EXPECT_NEAR(s.p, 0.05985319028797289, 1e-12);
}

TEST(MannWhitney, MatchesScipyOnSmallLargeAndTiedSamples) {
    // mannwhitneyu([1.1, 2.3, 3.8, 4.2, 5.9], [2.0, 4.5, 6.1, 6.6, 7.3, 8.8, 9.4],
    //              alternative='two-sided') -> U = 5.0, p = 0.04797979797979798 (exact)
    const auto small = stats::mannWhitneyU({1.1, 2.3, 3.8, 4.2, 5.9}, {2.0, 4.5, 6.1, 6.6, 7.3, 8.8, 9.4});
    EXPECT_TRUE(small.exact);
    EXPECT_DOUBLE_EQ(small.u, 5.0);
    EXPECT_NEAR(small.p, 0.04797979797979798, 1e-12);

    // mannwhitneyu([1, 2, 2, 3], [2, 3, 3, 4, 5], alternative='two-sided') -> U = 3.0,
    // p = 0.09934224785346528 (ties: asymptotic, tie- and continuity-corrected)
    const auto tied = stats::mannWhitneyU({1, 2, 2, 3}, {2, 3, 3, 4, 5});
    EXPECT_FALSE(tied.exact);
    EXPECT_DOUBLE_EQ(tied.u, 3.0);
    EXPECT_NEAR(tied.p, 0.09934224785346528, 1e-12);

    // mannwhitneyu(a, b, alternative='two-sided') with the 12 and 15 values below -> U = 38.0,
    // p = 0.011972878389045894 (both > 8: asymptotic; method='exact' gives 0.010208434720482102)
    const std::vector<double> a = {1.2, 3.4, 2.2, 5.6, 4.1, 3.3, 2.9, 4.8, 3.9, 2.5, 1.8, 4.4};
    const std::vector<double> b = {3.1, 4.9, 5.2, 3.8, 6.3, 4.7, 5.5, 2.6, 4.0, 5.9, 6.8, 3.6, 4.3, 5.0, 6.1};
    const auto large = stats::mannWhitneyU(a, b);
    EXPECT_FALSE(large.exact);
    EXPECT_DOUBLE_EQ(large.u, 38.0);
    EXPECT_NEAR(large.p, 0.011972878389045894, 1e-12);
    EXPECT_NEAR(stats::mannWhitneyUExact(a, b).p, 0.010208434720482102, 1e-12);
}

// The null distribution of U by brute force: every way to choose which n1 of
// the n1 + n2 ranks belong to the first sample.
std::vector<double> bruteUCounts(int n1, int n2) {
    std::vector<double> counts(size_t(n1) * size_t(n2) + 1, 0.0);
    const int n = n1 + n2;
    for (uint32_t mask = 0; mask < (1u << n); ++mask) {
        if (__builtin_popcount(mask) != n1) continue;
        // U1 = pairs (first-sample rank above second-sample rank).
        int u = 0, seenSecond = 0;
        for (int rank = 0; rank < n; ++rank) {
            if (mask >> rank & 1u) u += seenSecond;
            else ++seenSecond;
        }
        counts[size_t(u)] += 1;
    }
    return counts;
}

TEST(MannWhitney, UCountsMatchEnumeration) {
    for (auto [n1, n2] : std::vector<std::pair<int, int>>{{1, 1}, {1, 6}, {2, 2}, {3, 4}, {4, 3}, {5, 7}, {8, 8}, {2, 12}})
        EXPECT_EQ(stats::uCounts(n1, n2), bruteUCounts(n1, n2)) << n1 << " x " << n2;
}

TEST(MannWhitney, ExactPStaysCheapWithOneLongSample) {
    // 3 repetitions against 20,000 frames: exact by scipy's rule. The counts
    // must add up to C(20003, 3) and the sample entirely above the other must
    // get the smallest p there is, 2 / C(20003, 3).
    const auto counts = stats::uCounts(3, 20000);
    double total = 0;
    for (double c : counts) total += c;
    const double choose = 20003.0 * 20002.0 * 20001.0 / 6.0;
    EXPECT_NEAR(total / choose, 1.0, 1e-12);
    std::vector<double> frames;
    for (int i = 0; i < 20000; ++i) frames.push_back(1.0 + i * 1e-5);
    const auto r = stats::mannWhitneyU({5, 6, 7}, frames);
    EXPECT_TRUE(r.exact);
    EXPECT_NEAR(r.p / (2 / choose), 1.0, 1e-9);
}

// ---- Hodges-Lehmann shift and Moses' interval ----

std::vector<double> allDifferences(const std::vector<double>& before, const std::vector<double>& after) {
    std::vector<double> d;
    for (double y : after)
        for (double x : before) d.push_back(y - x);
    std::sort(d.begin(), d.end());
    return d;
}

// A deterministic generator, so that a failure reproduces everywhere.
struct Lcg {
    uint64_t state;
    double uniform() {   // in (0, 1)
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return (double(state >> 11) + 0.5) / 9007199254740992.0;
    }
};

TEST(HodgesLehmann, EveryOrderStatisticMatchesTheSortedDifferences) {
    Lcg g{7};
    for (int trial = 0; trial < 40; ++trial) {
        const size_t m = 1 + size_t(g.uniform() * 12), n = 1 + size_t(g.uniform() * 15);
        // Every third trial draws from a coarse grid, for ties and zero differences.
        const bool coarse = trial % 3 == 0;
        auto draw = [&] { return coarse ? std::round(g.uniform() * 5) * 0.25 : 0.3 + g.uniform() * g.uniform(); };
        std::vector<double> before(m), after(n);
        for (auto& v : before) v = draw();
        for (auto& v : after) v = draw();
        const auto d = allDifferences(before, after);
        std::vector<double> sb = before, sa = after;
        std::sort(sb.begin(), sb.end());
        std::sort(sa.begin(), sa.end());
        for (size_t k = 1; k <= d.size(); ++k)
            ASSERT_EQ(stats::kthPairwiseDifference(sb, sa, k), d[k - 1]) << "trial " << trial << " k " << k;
        const size_t mn = d.size();
        const double median = mn % 2 ? d[mn / 2] : 0.5 * (d[mn / 2 - 1] + d[mn / 2]);
        EXPECT_EQ(stats::hodgesLehmann(before, after, 0.05).shift, median) << "trial " << trial;
    }
}

TEST(HodgesLehmann, ExactIntervalMatchesR) {
    // R 4.2.2: x <- c(1.1, 2.3, 3.8, 4.2, 5.9); y <- c(2.0, 4.5, 6.1, 6.6, 7.3, 8.8, 9.4)
    // wilcox.test(y, x, conf.int = TRUE): difference in location 3.0999999999999996,
    // conf.int 0.19999999999999929 5.60000000000000053; with conf.level = 0.9: 0.3 5.5.
    const std::vector<double> x = {1.1, 2.3, 3.8, 4.2, 5.9}, y = {2.0, 4.5, 6.1, 6.6, 7.3, 8.8, 9.4};
    const auto r = stats::hodgesLehmann(x, y, 0.05);
    EXPECT_TRUE(r.exact);
    EXPECT_DOUBLE_EQ(r.shift, 3.0999999999999996);
    EXPECT_DOUBLE_EQ(r.low, 0.19999999999999929);
    EXPECT_DOUBLE_EQ(r.high, 5.60000000000000053);
    EXPECT_GE(r.confidence, 0.95);
    const auto r90 = stats::hodgesLehmann(x, y, 0.10);
    EXPECT_DOUBLE_EQ(r90.low, 0.3);
    EXPECT_DOUBLE_EQ(r90.high, 5.5);

    // x <- c(12.11, 12.51, 12.97); y <- 10.05 + 0.15 * (0:19)
    // wilcox.test(y, x, conf.int = TRUE): -1.0599999999999987, conf.int -2.159999999999998366 0.040000000000000924
    std::vector<double> frames;
    for (int i = 0; i < 20; ++i) frames.push_back(10.05 + 0.15 * i);
    const auto s = stats::hodgesLehmann({12.11, 12.51, 12.97}, frames, 0.05);
    EXPECT_TRUE(s.exact);
    EXPECT_DOUBLE_EQ(s.shift, -1.0599999999999987);
    EXPECT_DOUBLE_EQ(s.low, -2.159999999999998366);
    EXPECT_DOUBLE_EQ(s.high, 0.040000000000000924);

    // wilcox.test(c(3, 4), c(1, 2), conf.int = TRUE): 2, conf.int 1 3 with conf.level
    // 0.66666666666666674 ("Requested conf.level not achievable").
    const auto tiny = stats::hodgesLehmann({1, 2}, {3, 4}, 0.05);
    EXPECT_DOUBLE_EQ(tiny.shift, 2);
    EXPECT_DOUBLE_EQ(tiny.low, 1);
    EXPECT_DOUBLE_EQ(tiny.high, 3);
    EXPECT_NEAR(tiny.confidence, 2.0 / 3.0, 1e-12);
}

// How often the interval holds the true shift, over many pairs of samples
// drawn from one skewed distribution (frame times have a long right tail)
// with the second moved by `shift`.
double coverage(size_t m, size_t n, double shift, double alpha, bool quantized, bool& exactSeen) {
    Lcg g{12345};
    // A long right tail, as frame times have; quantized, it ties as timestamps do.
    // The shift is added before rounding, so on the grid it moves the law exactly.
    auto draw = [&](double by) {
        const double t = 1.0 - 0.2 * std::log(g.uniform()) + by;
        return quantized ? std::round(t * 20) / 20 : t;
    };
    int hits = 0;
    const int trials = 2000;
    for (int trial = 0; trial < trials; ++trial) {
        std::vector<double> before(m), after(n);
        for (auto& v : before) v = draw(0);
        for (auto& v : after) v = draw(shift);
        const auto r = stats::hodgesLehmann(before, after, alpha);
        exactSeen = exactSeen || r.exact;
        hits += r.low <= shift && shift <= r.high;
    }
    return double(hits) / trials;
}

TEST(HodgesLehmann, IntervalCoversTheTrueShiftAsOftenAsItSays) {
    bool exact = false;
    // Normal approximation, continuous data: close to the nominal 95%.
    const double normal = coverage(20, 25, 0.05, 0.05, false, exact);
    EXPECT_FALSE(exact);
    EXPECT_GT(normal, 0.93);
    EXPECT_LT(normal, 0.97);
    // Exact quantiles (5 against 7): at least the nominal level, as the step
    // function of U allows (the step just above the nominal level there).
    const double small = coverage(5, 7, 0.05, 0.05, false, exact);
    EXPECT_TRUE(exact);
    EXPECT_GT(small, 0.935);
    // Ties (a 0.05 grid of a unit near 1): the interval's ends are differences
    // on the grid, so it can only be wider than without ties.
    exact = false;
    const double tied = coverage(30, 30, 0.10, 0.05, true, exact);
    EXPECT_FALSE(exact);
    EXPECT_GT(tied, 0.93);
    // A 90% interval is narrower and covers less.
    const double ninety = coverage(20, 25, 0.05, 0.10, false, exact);
    EXPECT_GT(ninety, 0.87);
    EXPECT_LT(ninety, 0.93);
}

}  // namespace
}  // namespace cavity
