// How much did a change move the times, and how sure are we? The
// Hodges-Lehmann estimate (Hodges & Lehmann 1963) of the shift between two
// samples is the median of all pairwise differences new_j - old_i; Moses'
// interval (as in Hollander & Wolfe, "Nonparametric Statistical Methods",
// two-sample location) takes two of those differences, by order, as bounds.
// Both come from the ranks alone, like the Mann-Whitney U test they belong
// to, so the long tail of frame times does not drag them as it drags a
// difference of means, and the interval needs no normality.
#pragma once

#include "stats/namespace.h"
#include <cstddef>
#include <vector>

namespace cavity::stats {

struct ShiftEstimate {
    double shift;        // median of new_j - old_i; NaN when a sample is empty
    double low, high;    // the confidence interval of the shift
    // The interval's coverage as built. The exact U distribution is a step
    // function, so this is at least the 1 - alpha asked for, except when the
    // samples are too small to reach it: then the interval is the widest one
    // (smallest to largest difference) and this says how much it covers.
    double confidence;
    bool exact;          // bounds from the exact U quantiles, not the normal approximation
};

// The shift of `after` against `before` with a two-sided interval at
// confidence 1 - alpha. Exact U quantiles when either sample has at most 8
// values and there are no ties, the tie-corrected normal approximation with
// continuity correction otherwise: the same rule as mannWhitneyU, so the
// interval and the p-value read the same distribution. The exact interval is
// R's wilcox.test(after, before, conf.int = TRUE, exact = TRUE). NaNs are dropped.
ShiftEstimate hodgesLehmann(const std::vector<double>& before, const std::vector<double>& after, double alpha);

// The k-th smallest (1-based) of the differences after_j - before_i, both
// samples sorted ascending, found without forming the m n differences: 100,000
// frames on each side would be 10^10 of them. k in 1..m n.
double kthPairwiseDifference(const std::vector<double>& before, const std::vector<double>& after, size_t k);

}  // namespace cavity::stats
