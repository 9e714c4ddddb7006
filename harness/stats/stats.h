// Summary statistics of a sample of times, as reported per pass and per frame.
#pragma once

#include "stats/namespace.h"
#include <vector>

namespace cavity::stats {

struct Stats {
    int count = 0;
    double median = 0, min = 0, max = 0, mean = 0, p90 = 0, stddev = 0;
    double cv = 0;   // stddev / mean: the run-to-run noise a reader should expect
};

// Percentiles by linear interpolation between closest ranks; stddev is the
// sample (n - 1) deviation.
Stats summarize(std::vector<double> samples);
double percentile(std::vector<double> sorted, double p);

}  // namespace cavity::stats