// Change points in a series of times: E-divisive means (Matteson & James,
// "A nonparametric approach for multiple change point analysis of
// multivariate data", 2014) as Hunter / Apache Otava apply it to performance
// history (Fleming et al., "Hunter: Using Change Point Detection to Hunt for
// Performance Regressions", ICPE 2023). Our own implementation of that method:
//
//  split: over windows of `window` points, each half a window after the
//    last, E-divisive proposes the split that maximises the energy
//    statistic Q (pairwise |x_i - x_j| between the two sides against within
//    each) and keeps it while Student's t test between the segments either
//    side gives p below the first-pass level (10x alpha, as Otava), then
//    looks again inside the segments;
//  merge: the weak points of every window together; the one with the
//    largest p over alpha, or else the smallest change under min-change, is
//    dropped and its neighbours re-tested against their new segments, until
//    every point has p < alpha and a change of at least min-change.
//
// No random permutations: the same series gives the same points, and ties
// are broken towards the earlier index.
#pragma once

#include "history/namespace.h"

#include <cstddef>
#include <vector>

namespace cavity::history {

struct DetectorOptions {
    double alpha = 0.001;     // the t test's level a change point must reach
    double minChange = 0.02;  // |mean after / mean before - 1| a change point must reach
    size_t window = 50;       // points E-divisive looks at at once (Otava's default)
};

struct ChangePoint {
    size_t index = 0;         // the first point after the step
    double pValue = 1;
    double meanBefore = 0, meanAfter = 0;   // of the segments either side (to the neighbouring change points)
    double change() const { return meanBefore != 0 ? meanAfter / meanBefore - 1 : 0; }
};

std::vector<ChangePoint> detectChangePoints(const std::vector<double>& series, const DetectorOptions& options = {});

// The split of x[begin, end) that E-divisive proposes: the first index of
// its second side, with Q (0 when x[begin, end) has fewer than 2 points;
// then the index is `end`).
struct Candidate {
    size_t index = 0;
    double q = 0;
};
Candidate bestSplit(const std::vector<double>& x, size_t begin, size_t end);

}  // namespace cavity::history
