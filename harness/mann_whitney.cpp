#include "mann_whitney.h"

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

// Number of arrangements of n1 + n2 distinct values giving each U = 0..n1 n2,
// by the recurrence of Mann & Whitney 1947: the largest value belongs to
// either sample, c(n1, n2, u) = c(n1 - 1, n2, u - n2) + c(n1, n2 - 1, u).
std::vector<double> uCounts(int n1, int n2) {
    // row[j] holds c(i, j, .) for the current i.
    std::vector<std::vector<double>> row(size_t(n2) + 1);
    for (int j = 0; j <= n2; ++j) row[size_t(j)] = {1.0};   // c(0, j, 0) = 1
    for (int i = 1; i <= n1; ++i) {
        std::vector<std::vector<double>> next(size_t(n2) + 1);
        next[0] = {1.0};   // c(i, 0, 0) = 1
        for (int j = 1; j <= n2; ++j) {
            std::vector<double> c(size_t(i) * j + 1, 0.0);
            const auto& fromA = row[size_t(j)];      // c(i - 1, j, u - j)
            const auto& fromB = next[size_t(j - 1)]; // c(i, j - 1, u)
            for (size_t u = 0; u < fromA.size(); ++u) c[u + size_t(j)] += fromA[u];
            for (size_t u = 0; u < fromB.size(); ++u) c[u] += fromB[u];
            next[size_t(j)] = std::move(c);
        }
        row = std::move(next);
    }
    return row[size_t(n2)];
}

}  // namespace

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
    const bool small = a.size() <= 8 && b.size() <= 8;
    return small && rank(a, b).tieTerm == 0 ? mannWhitneyUExact(a, b) : mannWhitneyUAsymptotic(a, b);
}

}  // namespace cavity::stats
