// Student's two-sample t test (pooled variance), the significance test
// Hunter / Apache Otava put in place of the permutation test of
// Matteson & James's E-divisive: no random permutations, so the same series
// gives the same answer every time, and it holds up with a handful of points.
#pragma once

#include "history/namespace.h"

#include <cstddef>
#include <vector>

namespace cavity::history {

struct TTest {
    double t = 0;
    double p = 1;   // two-sided
    int df = 0;
    double meanA = 0, meanB = 0;
};

// a and b as two samples. Fewer than 3 values in all (df < 1): p = 1. Both
// without variance: p = 0 when their means differ, 1 when not.
TTest studentT(const double* a, size_t na, const double* b, size_t nb);

// P(|T| >= |t|) for T ~ Student's t with df degrees of freedom, through the
// regularized incomplete beta function.
double twoSidedP(double t, double df);

}  // namespace cavity::history
