// The Mann-Whitney U test (mann_whitney.h).
// Expected values come from the definitions, by arithmetic stated next to
// them, never from the code under test. CPU only.
#include "harness_names.h"
#include "stats/mann_whitney.h"
#include "image_patterns.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace cavity {

using namespace cavity::harness;
namespace {

using test::Lcg;
using test::pattern;
using test::withNoise;

// ---- Mann-Whitney U ----
// Expected values from this Python (no scipy), written apart from the C++:
// U by counting pairs, the normal approximation from the textbook formula,
// the exact p by enumerating every split of the pooled sample.
//
//   def u_pairs(a, b): return sum((x > y) + 0.5 * (x == y) for x in a for y in b)
//   def asym(a, b):
//       n1, n2 = len(a), len(b); n = n1 + n2; u1 = u_pairs(a, b); u = max(u1, n1*n2 - u1)
//       p = a + b; ties = sum(p.count(v)**3 - p.count(v) for v in set(p))
//       z = (u - n1*n2/2 - 0.5) / math.sqrt(n1*n2/12 * ((n+1) - ties/(n*(n-1))))
//       return u1, min(1.0, math.erfc(z / math.sqrt(2)))
//   def exact(a, b):
//       p = a + b; u1 = u_pairs(a, b); u = max(u1, len(a)*len(b) - u1); hit = tot = 0
//       for idx in itertools.combinations(range(len(p)), len(a)):
//           rest = [p[i] for i in range(len(p)) if i not in idx]
//           tot += 1; hit += u_pairs([p[i] for i in idx], rest) >= u
//       return u1, min(1.0, 2 * hit / tot)
//
// The first case is also scipy's: mannwhitneyu([1..5], [6..10]) gives
// p = 2/252 (exact) and 0.0121858 with method='asymptotic'.

TEST(MannWhitney, SeparatedSmallSamples) {
    const std::vector<double> a{1, 2, 3, 4, 5}, b{6, 7, 8, 9, 10};
    const auto asym = stats::mannWhitneyUAsymptotic(a, b);
    EXPECT_EQ(asym.u, 0.0);
    EXPECT_NEAR(asym.p, 0.0121857803553448, 1e-12);
    const auto exact = stats::mannWhitneyUExact(a, b);
    EXPECT_EQ(exact.u, 0.0);
    EXPECT_NEAR(exact.p, 2.0 / 252, 1e-15);
    const auto chosen = stats::mannWhitneyU(a, b);   // small, no ties: exact
    EXPECT_TRUE(chosen.exact);
    EXPECT_NEAR(chosen.p, 2.0 / 252, 1e-15);
    // Swapping the samples mirrors U and keeps p.
    const auto swapped = stats::mannWhitneyU(b, a);
    EXPECT_EQ(swapped.u, 25.0);
    EXPECT_NEAR(swapped.p, chosen.p, 1e-15);
}

TEST(MannWhitney, TiesUseTheCorrectedNormalApproximation) {
    const std::vector<double> a{1, 2, 2, 3, 4, 7}, b{2, 3, 4, 5, 5, 6, 8};
    const auto r = stats::mannWhitneyU(a, b);
    EXPECT_FALSE(r.exact);
    EXPECT_EQ(r.u, 11.0);
    EXPECT_NEAR(r.p, 0.170567192255758, 1e-12);
}

TEST(MannWhitney, InterleavedSamples) {
    const std::vector<double> a{0.8, 1.3, 2.2, 2.9, 3.1, 4.4, 5.0}, b{1.1, 1.7, 3.6, 3.9, 4.8, 5.5, 6.1, 7.2};
    EXPECT_EQ(stats::mannWhitneyU(a, b).u, 16.0);
    EXPECT_NEAR(stats::mannWhitneyUAsymptotic(a, b).p, 0.183232976928822, 1e-12);
    EXPECT_NEAR(stats::mannWhitneyUExact(a, b).p, 0.189277389277389, 1e-12);
}

TEST(MannWhitney, IdenticalSamplesGivePOne) {
    const std::vector<double> a{3.1, 2.7, 3.3, 2.9, 3.0, 3.2, 2.8, 3.4, 3.05, 2.95};
    const auto r = stats::mannWhitneyU(a, a);
    EXPECT_EQ(r.p, 1.0);
    EXPECT_EQ(r.u, 50.0);   // n1 n2 / 2
    EXPECT_EQ(stats::mannWhitneyU({1, 1, 1}, {1, 1, 1}).p, 1.0);   // all tied: no variance
    EXPECT_EQ(stats::mannWhitneyU({}, {1, 2}).p, 1.0);
}

TEST(MannWhitney, ShiftedLargeSamplesAreSignificant) {
    Lcg rng(42);
    std::vector<double> a, b;
    for (int i = 0; i < 200; ++i) {
        a.push_back(1.0 + 0.2 * rng.next());   // frame times, in ms
        b.push_back(1.1 + 0.2 * rng.next());   // a tenth of a ms slower
    }
    const auto r = stats::mannWhitneyU(a, b);
    EXPECT_FALSE(r.exact);
    EXPECT_LT(r.p, 1e-6);
    // Same distribution, different draws: not significant.
    std::vector<double> c;
    for (int i = 0; i < 200; ++i) c.push_back(1.0 + 0.2 * rng.next());
    EXPECT_GT(stats::mannWhitneyU(a, c).p, 0.001);
}

}  // namespace
}  // namespace cavity
