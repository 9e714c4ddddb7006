#include "history/edivisive.h"
#include "history/t_test.h"

#include <algorithm>
#include <cmath>
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

// Student's t between x[left, at) and x[at, right).
ChangePoint tested(const std::vector<double>& x, size_t left, size_t at, size_t right) {
    const TTest t = studentT(x.data() + left, at - left, x.data() + at, right - at);
    return {at, t.p, t.meanA, t.meanB};
}

// The segments' bounds: begin, each change point, end.
std::vector<size_t> bounds(const std::set<size_t>& points, size_t begin, size_t end) {
    std::vector<size_t> b{begin};
    b.insert(b.end(), points.begin(), points.end());
    b.push_back(end);
    return b;
}

// E-divisive on x[begin, end): the best split of any segment, kept while
// its t test passes `alpha`.
std::set<size_t> eDivisive(const std::vector<double>& x, size_t begin, size_t end, double alpha) {
    std::set<size_t> points;
    while (true) {
        const auto b = bounds(points, begin, end);
        Candidate best;
        size_t segment = b.size();
        for (size_t s = 0; s + 1 < b.size(); ++s) {
            const Candidate c = bestSplit(x, b[s], b[s + 1]);
            if (c.index < b[s + 1] && (segment == b.size() || c.q > best.q)) best = c, segment = s;
        }
        if (segment == b.size()) break;
        if (tested(x, b[segment], best.index, b[segment + 1]).pValue >= alpha) break;
        points.insert(best.index);
    }
    return points;
}

std::vector<ChangePoint> retest(const std::vector<double>& x, const std::vector<size_t>& at) {
    std::vector<ChangePoint> out;
    for (size_t i = 0; i < at.size(); ++i)
        out.push_back(tested(x, i ? at[i - 1] : 0, at[i], i + 1 < at.size() ? at[i + 1] : x.size()));
    return out;
}

}  // namespace

Candidate bestSplit(const std::vector<double>& x, size_t begin, size_t end) {
    Candidate best{end, 0};
    if (end < begin + 2) return best;
    const Distances d(x, begin, end);
    const size_t n = end - begin;
    bool found = false;
    for (size_t tau = 1; tau < n; ++tau)
        for (size_t kappa = tau + 1; kappa <= n; ++kappa) {
            const double q = energyQ(d, tau, kappa);
            if (!found || q > best.q) best = {begin + tau, q}, found = true;
        }
    return best;
}

std::vector<ChangePoint> detectChangePoints(const std::vector<double>& x, const DetectorOptions& o) {
    if (x.size() < 3) return {};
    // Split: windows half a window apart; each starts at least at the last
    // point the previous one found.
    const double firstPass = o.alpha < 0.05 ? o.alpha * 10 : std::min(1.0, o.alpha * 2);
    const size_t window = std::max<size_t>(o.window, 4), step = window / 2;
    std::set<size_t> weak;
    for (size_t start = 0; start < x.size();) {
        const size_t end = std::min(start + window, x.size());
        const auto found = eDivisive(x, start, end, firstPass);
        weak.insert(found.begin(), found.end());
        if (end == x.size()) break;
        start = std::max(found.empty() ? 0 : *found.rbegin(), start + step);
    }
    // Merge: drop the weakest until every point is significant and large enough.
    std::vector<size_t> at(weak.begin(), weak.end());
    auto points = retest(x, at);
    while (!points.empty()) {
        auto weakest = std::max_element(points.begin(), points.end(),
                                        [](const ChangePoint& a, const ChangePoint& b) { return a.pValue < b.pValue; });
        if (weakest->pValue < o.alpha) {
            weakest = std::min_element(points.begin(), points.end(), [](const ChangePoint& a, const ChangePoint& b) {
                return std::fabs(a.change()) < std::fabs(b.change());
            });
            if (std::fabs(weakest->change()) >= o.minChange) break;
        }
        at.erase(at.begin() + (weakest - points.begin()));
        points = retest(x, at);
    }
    return points;
}

}  // namespace cavity::history
