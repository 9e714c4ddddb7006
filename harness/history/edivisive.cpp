#include "history/edivisive.h"
#include "history/t_test.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace cavity::history {

namespace {

// Prefix sums of |x_i - x_j| over x[begin, end), so that the sum over any
// block of pairs is four look-ups: Q of every (tau, kappa) in O(n^2).
class Distances {
public:
    Distances(const std::vector<double>& x, size_t begin, size_t end) : n_(end - begin), p_((n_ + 1) * (n_ + 1), 0.0) {
        for (size_t i = 0; i < n_; ++i)
            for (size_t j = 0; j < n_; ++j)
                at(i + 1, j + 1) = std::fabs(x[begin + i] - x[begin + j]) + at(i, j + 1) + at(i + 1, j) - at(i, j);
    }
    // The sum of |x_i - x_j| over i in [r0, r1), j in [c0, c1) (relative indices).
    double block(size_t r0, size_t r1, size_t c0, size_t c1) const { return get(r1, c1) - get(r0, c1) - get(r1, c0) + get(r0, c0); }

private:
    double& at(size_t i, size_t j) { return p_[i * (n_ + 1) + j]; }
    double get(size_t i, size_t j) const { return p_[i * (n_ + 1) + j]; }
    size_t n_;
    std::vector<double> p_;
};

// Q(X, Y) for X = x[0, tau), Y = x[tau, kappa) relative to the segment:
// (n m / (n + m)) times the energy distance, written as Otava writes it.
double energyQ(const Distances& d, size_t tau, size_t kappa) {
    const double n = double(tau), m = double(kappa - tau);
    const double between = d.block(0, tau, tau, kappa);
    const double withinX = d.block(0, tau, 0, tau) / 2, withinY = d.block(tau, kappa, tau, kappa) / 2;
    double q = 2 / (n + m) * between;
    if (n > 1) q -= 2 * m / ((n + m) * (n - 1)) * withinX;
    if (m > 1) q -= 2 * n / ((n + m) * (m - 1)) * withinY;
    return q;
}

// Prefix sums of x and x^2: any segment's mean and squared error about it in O(1).
class Sums {
public:
    explicit Sums(const std::vector<double>& x) : s1_(x.size() + 1, 0.0), s2_(x.size() + 1, 0.0) {
        for (size_t i = 0; i < x.size(); ++i) {
            s1_[i + 1] = s1_[i] + x[i];
            s2_[i + 1] = s2_[i] + x[i] * x[i];
        }
    }
    double mean(size_t a, size_t b) const { return (s1_[b] - s1_[a]) / double(b - a); }
    // The squared error of x[a, b) about its mean; never below 0 (rounding).
    double sse(size_t a, size_t b) const {
        const double s = s1_[b] - s1_[a];
        return std::max(0.0, s2_[b] - s2_[a] - s * s / double(b - a));
    }

private:
    std::vector<double> s1_, s2_;
};

// The bounds of the model's segments: begin, each change point, end.
std::vector<size_t> bounds(const std::set<size_t>& points, size_t begin, size_t end) {
    std::vector<size_t> b{begin};
    for (size_t p : points)
        if (p > begin && p < end) b.push_back(p);
    b.push_back(end);
    return b;
}

// The test of x[left, at) against x[at, right) with the variance of the
// model whose segments are `model` (the residual about each segment's
// mean, over n - segments degrees of freedom), its p multiplied by the
// number of splits x[left, segmentEnd) offered.
ChangePoint tested(const Sums& s, const std::vector<size_t>& model, size_t left, size_t at, size_t right, size_t segmentEnd) {
    ChangePoint c;
    c.index = at;
    c.meanBefore = s.mean(left, at);
    c.meanAfter = s.mean(at, right);
    c.pointsBefore = at - left;
    c.pointsAfter = right - at;
    double sse = 0;
    for (size_t i = 0; i + 1 < model.size(); ++i) sse += s.sse(model[i], model[i + 1]);
    const size_t n = model.back() - model.front(), segments = model.size() - 1;
    if (n <= segments) return c;   // no degree of freedom left for the noise: p = 1
    const double df = double(n - segments);
    const double se = std::sqrt(sse / df * (1.0 / double(at - left) + 1.0 / double(right - at)));
    const double diff = c.meanAfter - c.meanBefore;
    // Relative to the values' size: sums of equal numbers leave rounding dust.
    const double scale = std::max(std::fabs(c.meanBefore), std::fabs(c.meanAfter));
    double p;
    if (se <= scale * 1e-12) p = std::fabs(diff) <= scale * 1e-12 ? 1.0 : 0.0;
    else p = twoSidedP(diff / se, df);
    c.pValue = std::min(1.0, p * double(segmentEnd - left - 1));
    return c;
}

// E-divisive on x[begin, end): of the splits each segment proposes, the one
// of largest Q whose test passes `level` is kept, until none passes.
std::set<size_t> eDivisive(const std::vector<double>& x, const Sums& s, size_t begin, size_t end, double level) {
    std::set<size_t> points;
    while (true) {
        const auto b = bounds(points, begin, end);
        Candidate best;
        bool found = false;
        for (size_t i = 0; i + 1 < b.size(); ++i) {
            const Candidate c = bestSplit(x, b[i], b[i + 1]);
            if (c.index >= b[i + 1] || (found && c.q <= best.q)) continue;
            std::set<size_t> trial = points;
            trial.insert(c.index);
            if (c.end < b[i + 1]) trial.insert(c.end);
            if (tested(s, bounds(trial, begin, end), b[i], c.index, c.end, b[i + 1]).pValue < level) best = c, found = true;
        }
        if (!found) break;
        points.insert(best.index);
    }
    return points;
}

// Each point against its neighbours in the model of all the points.
std::vector<ChangePoint> retest(const Sums& s, const std::vector<size_t>& at, size_t n, size_t settle) {
    std::set<size_t> all(at.begin(), at.end());
    const auto model = bounds(all, 0, n);
    std::vector<ChangePoint> out;
    for (size_t i = 0; i < at.size(); ++i) {
        out.push_back(tested(s, model, model[i], model[i + 1], model[i + 2], model[i + 2]));
        out.back().provisional = n - at[i] < settle;
    }
    return out;
}

// Each point moved to the least-squares split between its neighbours.
bool refine(const Sums& s, std::vector<size_t>& at, size_t n) {
    bool moved = false;
    for (size_t i = 0; i < at.size(); ++i) {
        const size_t left = i ? at[i - 1] : 0, right = i + 1 < at.size() ? at[i + 1] : n;
        size_t bestAt = at[i];
        double best = s.sse(left, at[i]) + s.sse(at[i], right);
        for (size_t j = left + 1; j < right; ++j) {
            const double e = s.sse(left, j) + s.sse(j, right);
            if (e < best * (1 - 1e-12)) best = e, bestAt = j;
        }
        if (bestAt != at[i]) at[i] = bestAt, moved = true;
    }
    return moved;
}

}  // namespace

Candidate bestSplit(const std::vector<double>& x, size_t begin, size_t end) {
    Candidate best{end, end, 0};
    if (end < begin + 2) return best;
    const Distances d(x, begin, end);
    const size_t n = end - begin;
    bool found = false;
    for (size_t tau = 1; tau < n; ++tau)
        for (size_t kappa = tau + 1; kappa <= n; ++kappa) {
            const double q = energyQ(d, tau, kappa);
            if (!found || q > best.q) best = {begin + tau, begin + kappa, q}, found = true;
        }
    return best;
}

std::vector<ChangePoint> detectChangePoints(const std::vector<double>& x, const DetectorOptions& o) {
    if (x.size() < 3) return {};
    const Sums s(x);
    // Split: windows half a window apart; each starts at least at the last
    // point the previous one found.
    const double firstPass = o.alpha < 0.05 ? o.alpha * 10 : std::min(1.0, o.alpha * 2);
    const size_t window = std::max<size_t>(o.window, 4), step = window / 2;
    std::set<size_t> weak;
    for (size_t start = 0; start < x.size();) {
        const size_t end = std::min(start + window, x.size());
        const auto found = eDivisive(x, s, start, end, firstPass);
        weak.insert(found.begin(), found.end());
        if (end == x.size()) break;
        start = std::max(found.empty() ? 0 : *found.rbegin(), start + step);
    }
    // Merge: drop the weakest until every point is significant at its level
    // and large enough; move each to its least-squares split; again until
    // nothing moves (a few rounds: each move only lowers the squared error).
    std::vector<size_t> at(weak.begin(), weak.end());
    const auto levelOf = [&](const ChangePoint& c) { return c.provisional ? o.alpha / 10 : o.alpha; };
    std::vector<ChangePoint> points;
    for (int round = 0; round < 8; ++round) {
        points = retest(s, at, x.size(), o.settle);
        while (!points.empty()) {
            auto worst = std::max_element(points.begin(), points.end(), [&](const ChangePoint& a, const ChangePoint& b) {
                return a.pValue / levelOf(a) < b.pValue / levelOf(b);
            });
            if (worst->pValue < levelOf(*worst)) {
                worst = std::min_element(points.begin(), points.end(), [](const ChangePoint& a, const ChangePoint& b) {
                    return std::fabs(a.change()) < std::fabs(b.change());
                });
                if (std::fabs(worst->change()) >= o.minChange) break;
            }
            at.erase(at.begin() + (worst - points.begin()));
            points = retest(s, at, x.size(), o.settle);
        }
        if (!refine(s, at, x.size())) break;
        at.erase(std::unique(at.begin(), at.end()), at.end());
    }
    return points;
}

}  // namespace cavity::history
