// LDR-FLIP after Andersson et al., HPG 2020 (flip.h): a colour pipeline and
// a feature pipeline, combined per pixel. Where the paper leaves a detail
// open (border handling, filter normalisation, the exact colour matrices) we
// follow NVIDIA's public reference implementation (github.com/NVlabs/flip,
// flip.py), so that our numbers can be checked against it.
#include "images/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace cavity::images::flip {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The paper's exponents of the colour (qc) and feature (qf) errors, and the
// colour-error redistribution that sends pc * cmax to pt.
constexpr double kQc = 0.7, kQf = 0.5, kPc = 0.4, kPt = 0.95;
// Peak-to-trough width (two standard deviations) of the human edge
// detector, in degrees of visual angle.
constexpr double kEdgeWidth = 0.082;

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<Vec3, 3>;

Vec3 mul(const Mat3& m, const Vec3& v) {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

Mat3 inverse(const Mat3& m) {
    const double a = m[0][0], b = m[0][1], c = m[0][2], d = m[1][0], e = m[1][1], f = m[1][2], g = m[2][0],
                 h = m[2][1], i = m[2][2];
    const double det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
    return {{{(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det},
             {(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det},
             {(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det}}};
}

// Linear sRGB (D65) to CIE XYZ, the reference implementation's exact
// fractions of the sRGB primaries; its inverse is computed, not rounded.
const Mat3 kRgbToXyz = {{{10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794},
                         {2613072.0 / 12288897, 8788810.0 / 12288897, 887015.0 / 12288897},
                         {1425312.0 / 73733382, 8788810.0 / 73733382, 70074185.0 / 73733382}}};
const Mat3 kXyzToRgb = inverse(kRgbToXyz);
// The D65 white point is what the matrix makes of RGB white (0.9504, 1, 1.0889).
const Vec3 kWhite = mul(kRgbToXyz, {1.0, 1.0, 1.0});

double srgbToLinearExact(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// The images FLIP judges are 8-bit: every channel is one of the 256 floats
// k / 255.0f. Those are looked up (the very values srgbToLinearExact gives
// them, computed once), sparing two images' worth of pow() calls, a fifth of
// a 1080p judge; any other value is computed.
double srgbToLinear(double c) {
    static const std::array<double, 256> table = [] {
        std::array<double, 256> t{};
        for (int k = 0; k < 256; ++k) t[size_t(k)] = srgbToLinearExact(double(float(k) / 255.0f));
        return t;
    }();
    const double k = std::nearbyint(c * 255.0);
    if (k >= 0 && k <= 255 && double(float(k) / 255.0f) == c) return table[size_t(k)];
    return srgbToLinearExact(c);
}

// YCxCz, the linearised CIELAB-like opponent space in which the paper's
// contrast sensitivity functions are defined: a linear transform of XYZ.
Vec3 xyzToYcxcz(const Vec3& xyz) {
    const double x = xyz[0] / kWhite[0], y = xyz[1] / kWhite[1], z = xyz[2] / kWhite[2];
    return {116 * y - 16, 500 * (x - y), 200 * (y - z)};
}

Vec3 ycxczToXyz(const Vec3& v) {
    const double y = (v[0] + 16) / 116, x = y + v[1] / 500, z = y - v[2] / 200;
    return {x * kWhite[0], y * kWhite[1], z * kWhite[2]};
}

Vec3 xyzToLab(const Vec3& xyz) {
    constexpr double delta = 6.0 / 29.0;
    auto f = [&](double t) { return t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0 / 29.0; };
    const double fx = f(xyz[0] / kWhite[0]), fy = f(xyz[1] / kWhite[1]), fz = f(xyz[2] / kWhite[2]);
    return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

// The Hunt effect (colourfulness grows with luminance): the paper scales
// the chromatic axes by 0.01 L.
Vec3 huntLab(const Vec3& linearRgb) {
    const Vec3 lab = xyzToLab(mul(kRgbToXyz, linearRgb));
    return {lab[0], 0.01 * lab[0] * lab[1], 0.01 * lab[0] * lab[2]};
}

// HyAB (Abasi, Amani Tehran, Fairchild 2020): city-block in lightness plus
// Euclidean in chroma, which the paper picks because it tracks large colour
// differences better than Euclidean distance in L*a*b*.
double hyab(const Vec3& p, const Vec3& q) {
    return std::fabs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
}

// A single-channel float plane.
struct Plane {
    int w = 0, h = 0;
    std::vector<float> v;
    Plane(int w_, int h_) : w(w_), h(h_), v(size_t(w_) * h_) {}
    float& operator()(int x, int y) { return v[size_t(y) * w + x]; }
    float operator()(int x, int y) const { return v[size_t(y) * w + x]; }
};

// Correlates src with kx along rows and ky along columns (both of odd
// length), repeating the edge pixels as the reference implementation pads.
// Both passes run along rows, so the inner loops are contiguous.
Plane separable(const Plane& src, const std::vector<double>& kx, const std::vector<double>& ky) {
    const int rx = int(kx.size()) / 2, ry = int(ky.size()) / 2, w = src.w, h = src.h;
    Plane tmp(w, h), out(w, h);
    std::vector<float> padded(size_t(w) + 2 * size_t(rx));
    std::vector<double> acc(static_cast<size_t>(w));
    for (int y = 0; y < h; ++y) {
        for (int x = -rx; x < w + rx; ++x) padded[size_t(x + rx)] = src(std::clamp(x, 0, w - 1), y);
        std::fill(acc.begin(), acc.end(), 0.0);
        for (size_t i = 0; i < kx.size(); ++i) {
            const double k = kx[i];
            const float* p = &padded[i];
            for (int x = 0; x < w; ++x) acc[size_t(x)] += k * p[x];
        }
        for (int x = 0; x < w; ++x) tmp(x, y) = float(acc[size_t(x)]);
    }
    for (int y = 0; y < h; ++y) {
        std::fill(acc.begin(), acc.end(), 0.0);
        for (int i = -ry; i <= ry; ++i) {
            const double k = ky[size_t(i + ry)];
            const float* t = &tmp.v[size_t(std::clamp(y + i, 0, h - 1)) * w];
            for (int x = 0; x < w; ++x) acc[size_t(x)] += k * t[x];
        }
        for (int x = 0; x < w; ++x) out(x, y) = float(acc[size_t(x)]);
    }
    return out;
}

// Each of the paper's contrast sensitivity functions is a sum of Gaussians in
// the spatial domain, S(x) = sum_k a_k sqrt(pi / b_k) exp(-pi^2 x^2 / b_k)
// (x in degrees), sampled on a square of radius 3 sqrt(b_max / (2 pi^2))
// degrees and normalised to sum 1. Parameters (a1, b1, a2, b2):
//   achromatic   1,    0.0047, 0,    -
//   red-green    1,    0.0053, 0,    -
//   blue-yellow 34.1,  0.04,  13.5,  0.025
// Each Gaussian is separable, so the 2D filter is a weighted sum of
// separable passes, with weights (a_k sqrt(pi / b_k) (sum of its 1D taps)^2) / total.
struct Csf {
    struct Term {
        double weight;
        std::vector<double> taps;   // normalised to sum 1
    };
    std::vector<Term> terms;
};

Csf makeCsf(std::initializer_list<std::pair<double, double>> ab, double ppd) {
    constexpr double bMax = 0.04;
    const int r = int(std::ceil(3 * std::sqrt(bMax / (2 * kPi * kPi)) * ppd));
    Csf csf;
    double total = 0;
    for (const auto& [a, b] : ab) {
        Csf::Term t;
        double sum = 0;
        for (int i = -r; i <= r; ++i) {
            const double xDeg = i / ppd;
            t.taps.push_back(std::exp(-kPi * kPi * xDeg * xDeg / b));
            sum += t.taps.back();
        }
        for (double& w : t.taps) w /= sum;
        t.weight = a * std::sqrt(kPi / b) * sum * sum;
        total += t.weight;
        csf.terms.push_back(std::move(t));
    }
    for (auto& t : csf.terms) t.weight /= total;
    return csf;
}

Plane applyCsf(const Plane& src, const Csf& csf) {
    if (csf.terms.size() == 1) return separable(src, csf.terms[0].taps, csf.terms[0].taps);
    Plane out(src.w, src.h);
    for (const auto& t : csf.terms) {
        const Plane p = separable(src, t.taps, t.taps);
        for (size_t i = 0; i < out.v.size(); ++i) out.v[i] += float(t.weight * p.v[i]);
    }
    return out;
}

// Edges and points are found with the first and second
// derivatives of a Gaussian of standard deviation sigma = 0.5 w PPD (w =
// 0.082 degrees) on a radius of ceil(3 sigma), positive weights normalised to
// sum 1 and negative ones to -1. The 2D kernel d(x) g(y) is separable and so
// is that normalisation: d's positive and negative parts each scaled, g to sum 1.
struct FeatureKernels {
    std::vector<double> gauss, edge, point;
};

FeatureKernels makeFeatureKernels(double ppd) {
    const double sd = 0.5 * kEdgeWidth * ppd;
    const int r = int(std::ceil(3 * sd));
    FeatureKernels k;
    for (int i = -r; i <= r; ++i) {
        const double g = std::exp(-(i * i) / (2 * sd * sd));
        k.gauss.push_back(g);
        k.edge.push_back(-i * g);
        k.point.push_back((i * i / (sd * sd) - 1) * g);
    }
    auto normalise = [](std::vector<double>& d) {
        double pos = 0, neg = 0;
        for (double x : d) (x > 0 ? pos : neg) += x;
        for (double& x : d) x = x > 0 ? x / pos : x < 0 ? x / -neg : 0.0;
    };
    double sum = 0;
    for (double g : k.gauss) sum += g;
    for (double& g : k.gauss) g /= sum;
    normalise(k.edge);
    normalise(k.point);
    return k;
}

// What the colour and feature pipelines need from one image.
struct Prepared {
    Plane huntL, huntA, huntB;   // CSF-filtered, Hunt-adjusted L*a*b*
    Plane edgeX, edgeY, pointX, pointY;
};

float inputValue(const HostImage& img, int x, int y, int c) {
    const float v = img.at(x, y, img.channels == 1 ? 0 : c);
    return std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
}

Prepared prepare(const HostImage& img, const Csf (&csf)[3], const FeatureKernels& fk) {
    const int w = img.width, h = img.height;
    Plane opp[3] = {Plane(w, h), Plane(w, h), Plane(w, h)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Vec3 rgb;
            for (int c = 0; c < 3; ++c) rgb[c] = srgbToLinear(inputValue(img, x, y, c));
            const Vec3 o = xyzToYcxcz(mul(kRgbToXyz, rgb));
            for (int c = 0; c < 3; ++c) opp[c](x, y) = float(o[c]);
        }

    // Colour pipeline: filter in YCxCz, back to linear RGB
    // clamped to the unit cube (the filtered colour may leave the gamut), then
    // Hunt-adjusted L*a*b*.
    Plane filtered[3] = {applyCsf(opp[0], csf[0]), applyCsf(opp[1], csf[1]), applyCsf(opp[2], csf[2])};
    Prepared p{Plane(w, h), Plane(w, h), Plane(w, h), Plane(w, h), Plane(w, h), Plane(w, h), Plane(w, h)};
    for (size_t i = 0; i < p.huntL.v.size(); ++i) {
        Vec3 rgb = mul(kXyzToRgb, ycxczToXyz({filtered[0].v[i], filtered[1].v[i], filtered[2].v[i]}));
        for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
        const Vec3 lab = huntLab(rgb);
        p.huntL.v[i] = float(lab[0]);
        p.huntA.v[i] = float(lab[1]);
        p.huntB.v[i] = float(lab[2]);
    }

    // Feature pipeline on the unfiltered achromatic channel,
    // normalised to [0, 1]: (Y + 16) / 116 is relative luminance.
    Plane lum(w, h);
    for (size_t i = 0; i < lum.v.size(); ++i) lum.v[i] = (opp[0].v[i] + 16.0f) / 116.0f;
    p.edgeX = separable(lum, fk.edge, fk.gauss);
    p.edgeY = separable(lum, fk.gauss, fk.edge);
    p.pointX = separable(lum, fk.point, fk.gauss);
    p.pointY = separable(lum, fk.gauss, fk.point);
    return p;
}

std::string shape(const HostImage& i) {
    return std::to_string(i.width) + "x" + std::to_string(i.height) + "x" + std::to_string(i.channels);
}

}  // namespace

cavity::Result<FlipResult> ldrFlip(const HostImage& reference, const HostImage& test, double ppd) {
    if (!reference.sameShape(test))
        return badInput("FLIP: reference is " + shape(reference) + ", test image is " + shape(test));
    if (reference.channels != 1 && reference.channels != 3 && reference.channels != 4)
        return badInput("FLIP needs 1, 3 or 4 channels, the images have " + std::to_string(reference.channels));
    if (reference.width <= 0 || reference.height <= 0) return badInput("FLIP: empty images (" + shape(reference) + ")");
    if (!(ppd > 0)) return badInput("FLIP: pixels per degree must be positive, got " + std::to_string(ppd));

    const Csf csf[3] = {makeCsf({{1.0, 0.0047}}, ppd), makeCsf({{1.0, 0.0053}}, ppd),
                        makeCsf({{34.1, 0.04}, {13.5, 0.025}}, ppd)};
    const FeatureKernels fk = makeFeatureKernels(ppd);
    const Prepared r = prepare(reference, csf, fk), t = prepare(test, csf, fk);

    // The largest colour error is the HyAB distance between
    // Hunt-adjusted green and blue; errors up to pc * cmax spread over
    // [0, pt], the rest over (pt, 1].
    const double cmax = std::pow(hyab(huntLab({0, 1, 0}), huntLab({0, 0, 1})), kQc);
    const double pcCmax = kPc * cmax;

    FlipResult out;
    out.errorMap = HostImage(reference.width, reference.height, 1);
    double sum = 0;
    for (size_t i = 0; i < out.errorMap.pixels.size(); ++i) {
        const double e = std::pow(hyab({r.huntL.v[i], r.huntA.v[i], r.huntB.v[i]},
                                       {t.huntL.v[i], t.huntA.v[i], t.huntB.v[i]}), kQc);
        const double colour = e < pcCmax ? (kPt / pcCmax) * e : kPt + (e - pcCmax) / (cmax - pcCmax) * (1.0 - kPt);
        // The larger of the edge and point differences, over the
        // largest possible (sqrt 2), to the power qf.
        const double de = std::fabs(std::hypot(r.edgeX.v[i], r.edgeY.v[i]) - std::hypot(t.edgeX.v[i], t.edgeY.v[i]));
        const double dp =
            std::fabs(std::hypot(r.pointX.v[i], r.pointY.v[i]) - std::hypot(t.pointX.v[i], t.pointY.v[i]));
        const double feature = std::pow(std::max(de, dp) / std::sqrt(2.0), kQf);
        // Feature differences push the colour error towards 1: dE = dEc^(1 - dEf).
        const double err = std::pow(colour, 1.0 - feature);
        out.errorMap.pixels[i] = float(err);
        sum += err;
    }
    out.mean = sum / double(out.errorMap.pixels.size());
    return out;
}

}  // namespace cavity::images::flip
