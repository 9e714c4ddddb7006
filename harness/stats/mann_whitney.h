// Did a change move the per-frame times? The Mann-Whitney U test (Mann &
// Whitney 1947) compares two samples by ranks alone, so it needs no
// normality and shrugs off the long tail of frame times that a t-test would not.
#pragma once

#include "stats/namespace.h"
#include <vector>

namespace cavity::stats {

struct MannWhitney {
    double u;             // U of the first sample: pairs (a_i, b_j) with a_i > b_j, ties counting 1/2
    double p;             // two-sided p-value
    bool exact = false;   // p from the exact distribution of U rather than the normal approximation
};

// Two-sided test, choosing as scipy.stats.mannwhitneyu(method='auto') does:
// the exact p when either sample has at most 8 values and no value occurs
// twice in the pooled sample, else the asymptotic one below. One small side
// is enough: with 3 repetitions against 50 frames the normal approximation is
// still poor in the tail where the verdict is decided, and the exact
// distribution is cheap (uCounts). NaNs are dropped; an empty sample gives
// u = 0, p = 1.
MannWhitney mannWhitneyU(const std::vector<double>& a, const std::vector<double>& b);

// Normal approximation with tie correction and continuity correction, as
// scipy.stats.mannwhitneyu(a, b, alternative='two-sided', method='asymptotic').
MannWhitney mannWhitneyUAsymptotic(const std::vector<double>& a, const std::vector<double>& b);

// Exact distribution of U (valid without ties), as scipy's method='exact'.
MannWhitney mannWhitneyUExact(const std::vector<double>& a, const std::vector<double>& b);

// How many of the C(n1 + n2, n1) orderings of n1 + n2 distinct values give
// U = 0, 1, ..., n1 n2: the null distribution of U, shared by the exact test
// and the exact Hodges-Lehmann interval. Exact integers while C(n1 + n2, n1)
// is below 2^53; past that a count is off by a few n1 n2 units in the last
// place of the largest one, far below any probability a verdict turns on.
std::vector<double> uCounts(int n1, int n2);

}  // namespace cavity::stats
