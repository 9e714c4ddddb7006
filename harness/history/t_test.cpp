#include "history/t_test.h"

#include <cmath>
#include <algorithm>
#include <limits>

namespace cavity::history {

namespace {

// The continued fraction of the incomplete beta function (modified Lentz),
// converging fast for x < (a + 1) / (a + b + 2).
double betaFraction(double a, double b, double x) {
    constexpr double kTiny = 1e-300, kEps = 1e-15;
    double c = 1, d = 1 - (a + b) * x / (a + 1);
    if (std::fabs(d) < kTiny) d = kTiny;
    d = 1 / d;
    double h = d;
    for (int m = 1; m <= 500; ++m) {
        const double m2 = 2.0 * m;
        // The even step, then the odd one.
        double aa = m * (b - m) * x / ((a + m2 - 1) * (a + m2));
        d = 1 + aa * d;
        d = std::fabs(d) < kTiny ? 1 / kTiny : 1 / d;
        c = 1 + aa / c;
        if (std::fabs(c) < kTiny) c = kTiny;
        h *= d * c;
        aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1));
        d = 1 + aa * d;
        d = std::fabs(d) < kTiny ? 1 / kTiny : 1 / d;
        c = 1 + aa / c;
        if (std::fabs(c) < kTiny) c = kTiny;
        const double step = d * c;
        h *= step;
        if (std::fabs(step - 1) < kEps) break;
    }
    return h;
}

// I_x(a, b), the regularized incomplete beta function.
double incompleteBeta(double a, double b, double x) {
    if (x <= 0) return 0;
    if (x >= 1) return 1;
    const double front =
        std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x));
    if (x < (a + 1) / (a + b + 2)) return front * betaFraction(a, b, x) / a;
    return 1 - front * betaFraction(b, a, 1 - x) / b;
}

void meanAndSquares(const double* v, size_t n, double& mean, double& squares) {
    mean = 0;
    for (size_t i = 0; i < n; ++i) mean += v[i];
    mean /= double(n);
    squares = 0;
    for (size_t i = 0; i < n; ++i) squares += (v[i] - mean) * (v[i] - mean);
}

}  // namespace

double twoSidedP(double t, double df) {
    if (!std::isfinite(t)) return 0;
    // P(|T| >= |t|) = I_{df / (df + t^2)}(df / 2, 1 / 2).
    return incompleteBeta(df / 2, 0.5, df / (df + t * t));
}

TTest studentT(const double* a, size_t na, const double* b, size_t nb) {
    TTest out;
    if (na == 0 || nb == 0) return out;
    double sa = 0, sb = 0;
    meanAndSquares(a, na, out.meanA, sa);
    meanAndSquares(b, nb, out.meanB, sb);
    out.df = int(na + nb) - 2;
    if (out.df < 1) return out;
    const double pooled = (sa + sb) / out.df;
    const double se = std::sqrt(pooled * (1.0 / double(na) + 1.0 / double(nb)));
    const double diff = out.meanB - out.meanA;
    // Relative to the values' size: sums of equal numbers leave rounding dust.
    const double scale = std::max(std::fabs(out.meanA), std::fabs(out.meanB));
    if (se <= scale * 1e-12) {
        out.p = std::fabs(diff) <= scale * 1e-12 ? 1.0 : 0.0;
        out.t = out.p == 0 ? std::copysign(std::numeric_limits<double>::infinity(), diff) : 0.0;
        return out;
    }
    out.t = diff / se;
    out.p = twoSidedP(out.t, out.df);
    return out;
}

}  // namespace cavity::history
