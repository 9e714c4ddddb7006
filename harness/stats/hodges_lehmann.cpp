#include "stats/hodges_lehmann.h"

#include "stats/mann_whitney.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace cavity::stats {

namespace {

std::vector<double> sortedWithoutNaN(const std::vector<double>& v) {
    std::vector<double> out;
    out.reserve(v.size());
    for (double x : v)
        if (!std::isnan(x)) out.push_back(x);
    std::sort(out.begin(), out.end());
    return out;
}

// Doubles mapped to integers in the same order, so a bisection over the
// integers visits every double between two bounds and ends on one of the
// differences in at most 64 steps.
uint64_t orderedKey(double d) {
    uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    return (bits >> 63) ? ~bits : bits | (uint64_t(1) << 63);
}

double fromOrderedKey(uint64_t key) {
    const uint64_t bits = (key >> 63) ? key & ~(uint64_t(1) << 63) : ~key;
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
}

// How many after_j - before_i are <= t. For one j the differences fall as
// before_i grows, so those <= t are a suffix of `before`; a larger after_j
// only shortens that suffix, so one pointer walks `before` once. Each
// difference is computed as written, so the count steps exactly at the
// floating-point differences the brute force would sort.
size_t countAtMost(const std::vector<double>& before, const std::vector<double>& after, double t) {
    size_t count = 0, i = 0;
    for (double y : after) {
        while (i < before.size() && y - before[i] > t) ++i;
        count += before.size() - i;
    }
    return count;
}

// Pooled sum of t^3 - t over groups of equal values (0: no ties).
double tieTerm(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> pooled(a);
    pooled.insert(pooled.end(), b.begin(), b.end());
    std::sort(pooled.begin(), pooled.end());
    double term = 0;
    for (size_t i = 0; i < pooled.size();) {
        size_t j = i;
        while (j < pooled.size() && pooled[j] == pooled[i]) ++j;
        const double t = double(j - i);
        term += t * t * t - t;
        i = j;
    }
    return term;
}

double normalCdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

// z with normalCdf(z) = p, by bisection: 200 halvings of [-40, 40] reach the
// resolution of a double, and this runs a handful of times per comparison.
double normalQuantile(double p) {
    double lo = -40, hi = 40;
    for (int i = 0; i < 200 && lo < hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (normalCdf(mid) < p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace

double kthPairwiseDifference(const std::vector<double>& before, const std::vector<double>& after, size_t k) {
    uint64_t lo = orderedKey(after.front() - before.back()), hi = orderedKey(after.back() - before.front());
    while (lo < hi) {
        const uint64_t mid = lo + (hi - lo) / 2;
        if (countAtMost(before, after, fromOrderedKey(mid)) >= k) hi = mid;
        else lo = mid + 1;
    }
    return fromOrderedKey(lo);
}

ShiftEstimate hodgesLehmann(const std::vector<double>& beforeIn, const std::vector<double>& afterIn, double alpha) {
    const auto before = sortedWithoutNaN(beforeIn), after = sortedWithoutNaN(afterIn);
    if (before.empty() || after.empty()) return {NAN, NAN, NAN, NAN, false};
    const size_t m = before.size(), n = after.size(), mn = m * n;
    auto d = [&](size_t k) { return kthPairwiseDifference(before, after, k); };
    const double shift = mn % 2 ? d(mn / 2 + 1) : 0.5 * (d(mn / 2) + d(mn / 2 + 1));

    // The interval is [d_(k), d_(mn + 1 - k)]: the shift lies below d_(k)
    // exactly when at most k - 1 of the shifted differences are <= 0, and
    // under H0 that count has the distribution of U, so the coverage is
    // 1 - 2 P(U <= k - 1).
    const double ties = tieTerm(before, after);
    const bool exact = (m <= 8 || n <= 8) && ties == 0;
    size_t k = 1;
    double below = 0;   // P(U <= k - 1)
    if (exact) {
        // k: the smallest u with P(U <= u) >= alpha / 2 (R's qwilcox, with its
        // allowance for rounding), so that P(U <= k - 1) < alpha / 2.
        const auto counts = uCounts(int(m), int(n));
        double total = 0;
        for (double c : counts) total += c;
        double cdf = 0;
        size_t u = 0;
        for (; u < counts.size(); ++u) {
            if (cdf + counts[u] / total >= alpha / 2 - 1e-12) break;
            cdf += counts[u] / total;
        }
        k = std::max<size_t>(u, 1);
        below = 0;
        for (size_t v = 0; v < k; ++v) below += counts[v] / total;
    } else {
        // P(U <= k - 1) ~ Phi((k - 1 + 1/2 - mn/2) / sigma), continuity
        // corrected; the largest k that keeps it within alpha / 2.
        const double N = double(m + n);
        const double var = double(mn) / 12 * ((N + 1) - ties / (N * (N - 1)));
        const double sigma = std::sqrt(std::max(var, 0.0));
        const double z = normalQuantile(1 - alpha / 2);
        const double kReal = std::floor(double(mn) / 2 + 0.5 - z * sigma);
        k = kReal < 1 ? 1 : size_t(kReal);
        below = sigma > 0 ? normalCdf((double(k) - 0.5 - double(mn) / 2) / sigma) : 0.5;
    }
    return {shift, d(k), d(mn + 1 - k), std::clamp(1 - 2 * below, 0.0, 1.0), exact};
}

}  // namespace cavity::stats
