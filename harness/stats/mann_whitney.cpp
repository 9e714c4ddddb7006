#include "stats/mann_whitney.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace cavity::stats {

namespace {

std::vector<double> withoutNaN(const std::vector<double>& v) {
    std::vector<double> out;
    out.reserve(v.size());
    for (double x : v)
        if (!std::isnan(x)) out.push_back(x);
    return out;
}

struct Ranked {
    double u1 = 0;        // U of the first sample
    double tieTerm = 0;   // sum over groups of tied values of t^3 - t
};

// Ranks of the pooled sample, ties given their average rank; then
// U1 = R1 - n1 (n1 + 1) / 2 with R1 the first sample's rank sum.
Ranked rank(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<std::pair<double, bool>> pooled;   // value, from a
    for (double x : a) pooled.emplace_back(x, true);
    for (double x : b) pooled.emplace_back(x, false);
    std::sort(pooled.begin(), pooled.end(), [](const auto& l, const auto& r) { return l.first < r.first; });
    Ranked r;
    double rankSumA = 0;
    for (size_t i = 0; i < pooled.size();) {
        size_t j = i;
        while (j < pooled.size() && pooled[j].first == pooled[i].first) ++j;
        const double t = double(j - i), averageRank = (double(i + 1) + double(j)) / 2;
        for (size_t k = i; k < j; ++k)
            if (pooled[k].second) rankSumA += averageRank;
        r.tieTerm += t * t * t - t;
        i = j;
    }
    const double n1 = double(a.size());
    r.u1 = rankSumA - n1 * (n1 + 1) / 2;
    return r;
}

// Upper tail of the standard normal.
double normalSf(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

}  // namespace

// The count of arrangements with U = u is the number of partitions of u into
// at most n1 parts none larger than n2, the coefficient of q^u in the Gaussian
// binomial [n1 + n2 choose n1]_q = prod_{i=1..m} (1 - q^(n+i)) / (1 - q^i),
// m = min(n1, n2), n = max(n1, n2). Building it one factor at a time costs
// m^2 n steps, so a 3-repetition run against 50,000 frames stays instant;
// the pairwise recurrence of Mann & Whitney 1947 costs (n1 n2)^2 / 4.
std::vector<double> uCounts(int n1, int n2) {
    const size_t m = size_t(std::max(0, std::min(n1, n2))), n = size_t(std::max(0, std::max(n1, n2)));
    std::vector<double> c(m * n + 1, 0.0);
    c[0] = 1.0;
    for (size_t i = 1; i <= m; ++i) {
        // Times (1 - q^(n+i)): from the top down, so each term reads the old value.
        // Terms past degree i n cancel in the division below, so they are never formed.
        const size_t shift = n + i;
        for (size_t k = i * n; k >= shift; --k) c[k] -= c[k - shift];
        // Divided by (1 - q^i): r[k] = c[k] + r[k - i], from the bottom up.
        for (size_t k = i; k <= i * n; ++k) c[k] += c[k - i];
    }
    return c;
}

// Under H0, U has mean n1 n2 / 2 and variance n1 n2 / 12 ((n + 1) - sum(t^3 - t) / (n (n - 1)))
// (tie-corrected). scipy takes U = max(U1, U2) for the two-sided test,
// subtracts 0.5 for continuity and doubles the upper tail.
MannWhitney mannWhitneyUAsymptotic(const std::vector<double>& aIn, const std::vector<double>& bIn) {
    const auto a = withoutNaN(aIn), b = withoutNaN(bIn);
    if (a.empty() || b.empty()) return {0.0, 1.0};
    const Ranked r = rank(a, b);
    const double n1 = double(a.size()), n2 = double(b.size()), n = n1 + n2;
    const double u = std::max(r.u1, n1 * n2 - r.u1);
    const double var = n1 * n2 / 12 * ((n + 1) - r.tieTerm / (n * (n - 1)));
    if (!(var > 0)) return {r.u1, 1.0};   // every value tied: no evidence either way
    const double z = (u - n1 * n2 / 2 - 0.5) / std::sqrt(var);
    return {r.u1, std::clamp(2 * normalSf(z), 0.0, 1.0)};
}

MannWhitney mannWhitneyUExact(const std::vector<double>& aIn, const std::vector<double>& bIn) {
    const auto a = withoutNaN(aIn), b = withoutNaN(bIn);
    if (a.empty() || b.empty()) return {0.0, 1.0, true};
    const Ranked r = rank(a, b);
    const int n1 = int(a.size()), n2 = int(b.size());
    const auto counts = uCounts(n1, n2);
    const double u = std::max(r.u1, double(n1) * n2 - r.u1);
    double tail = 0, total = 0;
    for (size_t k = 0; k < counts.size(); ++k) {
        total += counts[k];
        if (double(k) >= u) tail += counts[k];   // P(U >= u)
    }
    return {r.u1, std::clamp(2 * tail / total, 0.0, 1.0), true};
}

MannWhitney mannWhitneyU(const std::vector<double>& aIn, const std::vector<double>& bIn) {
    const auto a = withoutNaN(aIn), b = withoutNaN(bIn);
    if (a.empty() || b.empty()) return {0.0, 1.0};
    const bool small = a.size() <= 8 || b.size() <= 8;
    return small && rank(a, b).tieTerm == 0 ? mannWhitneyUExact(a, b) : mannWhitneyUAsymptotic(a, b);
}

}  // namespace cavity::stats
