// Change points in a series of times: E-divisive means (Matteson & James,
// "A nonparametric approach for multiple change point analysis of
// multivariate data", 2014) as Hunter / Apache Otava apply it to performance
// history (Fleming et al., "Hunter: Using Change Point Detection to Hunt for
// Performance Regressions", ICPE 2023), with a significance test per
// segment. Our own implementation of that method:
//
//  split: over windows of `window` points, each half a window after the
//    last, E-divisive proposes the (tau, kappa) that maximises the energy
//    statistic Q between x[begin, tau) and x[tau, kappa), and keeps tau
//    while the test of those two sides passes the first-pass level (10x
//    alpha, as Otava's weak points), then looks again inside the segments.
//    Testing against x[tau, kappa) rather than all of x[tau, end) is what
//    finds a regression that was reverted a few commits later: the commits
//    after the revert would otherwise dilute the excursion.
//  test: the difference of the two segments' means over its standard error,
//    with the noise of the whole series (the pooled variance about every
//    segment's mean, the model's residual) rather than of the two segments
//    alone: a series' commit-to-commit noise is one property of its
//    runner, and a three-commit segment cannot estimate it. The p value of
//    the best of m candidate splits is multiplied by m (Bonferroni), so a
//    flat series' most extreme split, often at an end, is judged as the
//    maximum it is.
//  merge: the point whose adjusted p is furthest over its level is dropped,
//    or else the smallest change under min-change, and its neighbours are
//    re-tested against their new segments; then each point moves to the
//    split of its segment with the least squared error (the step's least
//    squares location), until nothing changes.
//  the newest commits: a point with fewer than `settle` commits after it
//    must reach alpha / 10, and is reported as provisional. One slow run at
//    the head of a series is the commonest false alarm a CI job can raise.
//
// No random permutations: the same series gives the same points, and ties
// are broken towards the earlier index.
#pragma once

#include "history/namespace.h"

#include <cstddef>
#include <vector>

namespace cavity::history {

struct DetectorOptions {
    double alpha = 0.001;     // the adjusted p a change point must reach
    double minChange = 0.01;  // |mean after / mean before - 1| a change point must reach
    size_t window = 50;       // points E-divisive looks at at once (Otava's default)
    size_t settle = 3;        // commits after a point before it is judged at alpha (fewer: alpha / 10)
};

struct ChangePoint {
    size_t index = 0;         // the first point after the step
    double pValue = 1;        // adjusted for the number of splits its segment offered
    double meanBefore = 0, meanAfter = 0;   // of the segments either side (to the neighbouring change points)
    size_t pointsBefore = 0, pointsAfter = 0;   // the lengths of those segments
    bool provisional = false;  // fewer than `settle` points after it in the series
    double change() const { return meanBefore != 0 ? meanAfter / meanBefore - 1 : 0; }
};

std::vector<ChangePoint> detectChangePoints(const std::vector<double>& series, const DetectorOptions& options = {});

// The split of x[begin, end) that E-divisive proposes: the first index of
// its second side (`index`), the end of that side (`end`; the excursion
// x[index, end) when it returns before `end`), with Q (0 when x[begin, end)
// has fewer than 2 points; then the index is `end`).
struct Candidate {
    size_t index = 0;
    size_t end = 0;
    double q = 0;
};
Candidate bestSplit(const std::vector<double>& x, size_t begin, size_t end);

}  // namespace cavity::history
