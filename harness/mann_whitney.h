// Did a change move the per-frame times? The Mann-Whitney U test (Mann &
// Whitney 1947) compares two samples by ranks alone, so it needs no
// normality and shrugs off the long tail of frame times that a t-test would not.
#pragma once

#include <vector>

namespace cavity::stats {

struct MannWhitney {
    double u;             // U of the first sample: pairs (a_i, b_j) with a_i > b_j, ties counting 1/2
    double p;             // two-sided p-value
    bool exact = false;   // p from the exact distribution of U rather than the normal approximation
};

// Two-sided test: the exact p when both samples have at most 8 values and
// there are no ties, else the asymptotic one below. (scipy's default
// method='auto' also goes exact for small samples without ties, from a
// threshold that has moved between versions.) NaNs are dropped; an empty
// sample gives u = 0, p = 1.
MannWhitney mannWhitneyU(const std::vector<double>& a, const std::vector<double>& b);

// Normal approximation with tie correction and continuity correction, as
// scipy.stats.mannwhitneyu(a, b, alternative='two-sided', method='asymptotic').
MannWhitney mannWhitneyUAsymptotic(const std::vector<double>& a, const std::vector<double>& b);

// Exact distribution of U (valid without ties), as scipy's method='exact'.
MannWhitney mannWhitneyUExact(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace cavity::stats
