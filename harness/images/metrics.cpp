#include "images/metrics.h"

#include "images/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace cavity::images::metrics {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string shape(const HostImage& i) {
    return std::to_string(i.width) + "x" + std::to_string(i.height) + "x" + std::to_string(i.channels);
}

// OIIO's compare counts a NaN as matching a NaN and an Inf an Inf; keep that,
// but only for Infs of the same sign.
bool sameNonFinite(float a, float b) {
    return (std::isnan(a) && std::isnan(b)) || (std::isinf(a) && a == b);
}

// The sums of an image comparison, as OpenImageIO's ImageBufAlgo::compare
// defines them (2.4, imagebufalgo_compare.cpp), for images without
// non-finite values: over every channel of every pixel, the largest
// |a - b| (and the first pixel where it occurs), the mean and the root mean
// square of |a - b|, and the pixels with any channel's |a - b| above the
// threshold. Our own code rather than OpenImageIO's since the judge also
// runs where OpenImageIO is not installed (cavity_render on a GPU machine);
// it sums in one order, so the same images give the same bits everywhere.
// Its PSNR is left out: OpenImageIO uses max(1, largest value seen) as the
// peak, and ours is for a signal range of 1.0 whatever the values.
struct Sums {
    double maxAbs = 0, meanAbs = 0, rmse = 0;
    long long overThreshold = 0;
    int worstX = 0, worstY = 0;
};

Sums sums(const HostImage& a, const HostImage& b, double threshold) {
    Sums s;
    const double limit = float(threshold);
    const size_t ch = size_t(a.channels), npix = size_t(a.width) * size_t(a.height);
    double total = 0, total2 = 0;
    size_t worst = 0;
    for (size_t p = 0; p < npix; ++p) {
        bool over = false;
        for (size_t c = 0; c < ch; ++c) {
            const double f = std::fabs(a.pixels[p * ch + c] - b.pixels[p * ch + c]);
            total += f;
            total2 += f * f;
            if (f > s.maxAbs) {
                s.maxAbs = f;
                worst = p;
            }
            over |= f > limit;
        }
        s.overThreshold += over;
    }
    const double n = double(npix * ch);
    s.meanAbs = total / n;
    s.rmse = std::sqrt(total2 / n);
    s.worstX = int(worst % size_t(a.width));
    s.worstY = int(worst / size_t(a.width));
    return s;
}

long long nonFinitePixels(const HostImage& img) {
    long long n = 0;
    const size_t ch = size_t(img.channels);
    for (size_t p = 0; p * ch < img.pixels.size(); ++p)
        n += std::any_of(img.pixels.begin() + long(p * ch), img.pixels.begin() + long(p * ch + ch),
                         [](float v) { return !std::isfinite(v); });
    return n;
}

// With non-finite values present, compare copies in which every pair holding
// one is zeroed in both images, then take those pairs out of the averages and
// put the mismatched ones back in as infinite, over-threshold errors.
Sums compareWithNonFinite(const HostImage& a, const HostImage& b, double threshold) {
    HostImage sa = a, sb = b;
    const size_t npix = size_t(a.width) * a.height;
    const int ch = a.channels;
    size_t excluded = 0;
    long long firstMismatch = -1;
    std::vector<size_t> mismatchedPixels;
    for (size_t p = 0; p < npix; ++p) {
        bool mismatch = false;
        for (int c = 0; c < ch; ++c) {
            const size_t i = p * ch + c;
            const float x = a.pixels[i], y = b.pixels[i];
            if (std::isfinite(x) && std::isfinite(y)) continue;
            mismatch |= !sameNonFinite(x, y);
            sa.pixels[i] = sb.pixels[i] = 0.0f;
            ++excluded;
        }
        if (mismatch) {
            if (firstMismatch < 0) firstMismatch = (long long)p;
            mismatchedPixels.push_back(p);
        }
    }
    Sums s = sums(sa, sb, threshold);
    const double nvals = double(npix) * ch, used = nvals - double(excluded);
    s.meanAbs = used > 0 ? s.meanAbs * nvals / used : 0.0;
    s.rmse = used > 0 ? std::sqrt(s.rmse * s.rmse * nvals / used) : 0.0;
    for (size_t p : mismatchedPixels) {
        bool counted = false;   // by sums(), through another channel of the pixel
        for (int c = 0; c < ch; ++c)
            counted |= std::fabs(sa.pixels[p * ch + c] - sb.pixels[p * ch + c]) > float(threshold);
        s.overThreshold += !counted;
    }
    if (firstMismatch >= 0) {
        s.maxAbs = kInf;
        s.worstX = int(firstMismatch % a.width);
        s.worstY = int(firstMismatch / a.width);
    }
    return s;
}

// What SSIM and FLIP see: non-finite values as 0.
HostImage finiteCopy(const HostImage& img) {
    HostImage out = img;
    for (float& v : out.pixels)
        if (!std::isfinite(v)) v = 0.0f;
    return out;
}

// The 11-tap Gaussian window of Wang et al. 2004 (sigma 1.5), normalised; as
// a separable filter it is the paper's 11x11 circular-symmetric window.
constexpr int kSsimRadius = 5;

std::array<double, 2 * kSsimRadius + 1> ssimWindow() {
    std::array<double, 2 * kSsimRadius + 1> w{};
    double sum = 0;
    for (int i = -kSsimRadius; i <= kSsimRadius; ++i) sum += w[i + kSsimRadius] = std::exp(-i * i / (2 * 1.5 * 1.5));
    for (double& x : w) x /= sum;
    return w;
}

// Horizontal pass of the window over one row of each of the five moment
// images (x, y, x^2, y^2, xy), edges clamped; out holds 5 rows of w. The loop
// over x is innermost so that it vectorises.
void blurRowMoments(const float* a, const float* b, int stride, int w, double* out) {
    static const auto win = ssimWindow();
    constexpr int r = kSsimRadius;
    std::fill(out, out + 5 * size_t(w), 0.0);
    thread_local std::vector<double> px, py;
    px.resize(size_t(w) + 2 * r);
    py.resize(size_t(w) + 2 * r);
    for (int x = -r; x < w + r; ++x) {
        const size_t i = size_t(std::clamp(x, 0, w - 1)) * stride;
        px[size_t(x + r)] = a[i];
        py[size_t(x + r)] = b[i];
    }
    for (int i = 0; i <= 2 * r; ++i) {
        const double k = win[size_t(i)];
        const double* sx = &px[size_t(i)];
        const double* sy = &py[size_t(i)];
        for (int x = 0; x < w; ++x) {
            out[x] += k * sx[x];
            out[w + x] += k * sy[x];
            out[2 * w + x] += k * sx[x] * sx[x];
            out[3 * w + x] += k * sy[x] * sy[x];
            out[4 * w + x] += k * sx[x] * sy[x];
        }
    }
}

}  // namespace

// Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image quality
// assessment: from error visibility to structural similarity", IEEE TIP 13(4),
// 2004: local means, variances and covariance under a Gaussian window
// (11x11, sigma 1.5), SSIM = (2 ux uy + C1)(2 sxy + C2) / ((ux^2 + uy^2 + C1)(sx^2 + sy^2 + C2)),
// C1 = (0.01 L)^2, C2 = (0.03 L)^2 with L = 1, averaged over the pixels
// where the whole window lies inside the image (the 'valid' region of the
// authors' ssim_index.m, also what scikit-image averages). Images smaller
// than the window are averaged over every pixel, with clamped edges.
double ssim(const HostImage& a, const HostImage& b) {
    constexpr double C1 = 0.01 * 0.01, C2 = 0.03 * 0.03;
    static const auto win = ssimWindow();
    const int w = a.width, h = a.height, ch = a.channels;
    if (w <= 0 || h <= 0 || ch <= 0) return 1.0;
    const bool valid = w > 2 * kSsimRadius && h > 2 * kSsimRadius;
    const int x0 = valid ? kSsimRadius : 0, x1 = valid ? w - kSsimRadius : w;
    const int y0 = valid ? kSsimRadius : 0, y1 = valid ? h - kSsimRadius : h;
    const size_t row = 5 * size_t(w);
    // The horizontal pass's rows in a ring of 2r + 1: the vertical pass at
    // row y reads rows y - r .. y + r (clamped), and y only grows. A whole
    // image of them would be 5 doubles a pixel (83 MB at 1920x1080), paged
    // in and zeroed for every channel.
    constexpr int kRing = 2 * kSsimRadius + 1;
    std::vector<double> ring(row * kRing), m(row);
    std::array<int, kRing> held;
    double total = 0;
    for (int c = 0; c < ch; ++c) {
        held.fill(-1);
        const auto horizontal = [&](int y) -> const double* {
            double* slot = &ring[row * size_t(y % kRing)];
            if (held[size_t(y % kRing)] != y) {
                const size_t first = size_t(y) * w * ch + c;
                blurRowMoments(&a.pixels[first], &b.pixels[first], ch, w, slot);
                held[size_t(y % kRing)] = y;
            }
            return slot;
        };
        double sum = 0;
        for (int y = y0; y < y1; ++y) {
            std::fill(m.begin(), m.end(), 0.0);
            for (int i = -kSsimRadius; i <= kSsimRadius; ++i) {
                const double k = win[size_t(i + kSsimRadius)];
                const double* t = horizontal(std::clamp(y + i, 0, h - 1));
                for (size_t j = 0; j < row; ++j) m[j] += k * t[j];
            }
            for (int x = x0; x < x1; ++x) {
                const double ux = m[size_t(x)], uy = m[size_t(w + x)];
                const double sx = m[size_t(2 * w + x)] - ux * ux, sy = m[size_t(3 * w + x)] - uy * uy;
                const double sxy = m[size_t(4 * w + x)] - ux * uy;
                // Written so that x == y gives exactly 1: 2*ux*uy == ux*ux + uy*uy
                // and 2*sxy == sx + sy hold bit for bit then.
                sum += ((2 * ux * uy + C1) * (2 * sxy + C2)) / ((ux * ux + uy * uy + C1) * (sx + sy + C2));
            }
        }
        total += sum / (double(x1 - x0) * (y1 - y0));
    }
    return total / ch;
}

namespace {

// RGBA whose alpha holds one value in both images: the RGB channels alone.
bool constantAlpha(const HostImage& a, const HostImage& b) {
    if (a.channels != 4) return false;
    const float alpha = a.pixels[3];
    for (const HostImage* img : {&a, &b})
        for (size_t i = 3; i < img->pixels.size(); i += 4)
            if (!(img->pixels[i] == alpha)) return false;
    return true;
}

HostImage colourOnly(const HostImage& img) {
    HostImage out(img.width, img.height, 3);
    for (size_t p = 0; p < size_t(img.width) * size_t(img.height); ++p)
        for (int c = 0; c < 3; ++c) out.pixels[p * 3 + size_t(c)] = img.pixels[p * 4 + size_t(c)];
    return out;
}

long long differing(const HostImage& a, const HostImage& b, int delta) {
    long long n = 0;
    const size_t channels = size_t(a.channels);
    for (size_t p = 0; p * channels < a.pixels.size(); ++p)
        for (size_t c = 0; c < channels; ++c) {
            const float x = a.pixels[p * channels + c], y = b.pixels[p * channels + c];
            // Both were stored as 8-bit codes; a non-finite value differs.
            const bool differs = !std::isfinite(x) || !std::isfinite(y) ||
                                 std::abs(std::lround(x * 255.0f) - std::lround(y * 255.0f)) > delta;
            if (differs) {
                ++n;
                break;
            }
        }
    return n;
}

}  // namespace

Result<Report> compare(const HostImage& baselineIn, const HostImage& candidateIn, const Options& options) {
    if (!baselineIn.sameShape(candidateIn))
        return badInput("baseline is " + shape(baselineIn) + ", new image is " + shape(candidateIn));
    for (const HostImage* img : {&baselineIn, &candidateIn})
        if (img->pixels.size() != size_t(img->width) * img->height * img->channels)
            return internal("image " + shape(*img) + " holds " + std::to_string(img->pixels.size()) + " floats");
    if (baselineIn.width <= 0 || baselineIn.height <= 0 || baselineIn.channels <= 0)
        return badInput("cannot compare empty images (" + shape(baselineIn) + ")");
    const bool dropAlpha = constantAlpha(baselineIn, candidateIn);
    const HostImage rgbBaseline = dropAlpha ? colourOnly(baselineIn) : HostImage{};
    const HostImage rgbCandidate = dropAlpha ? colourOnly(candidateIn) : HostImage{};
    const HostImage& baseline = dropAlpha ? rgbBaseline : baselineIn;
    const HostImage& candidate = dropAlpha ? rgbCandidate : candidateIn;

    Report r{};
    r.channelsCompared = candidate.channels;
    if (options.eightBit) {
        r.differingPixels = differing(baseline, candidate, options.differingDelta);
        r.differingShare = double(r.differingPixels) / (double(baseline.width) * baseline.height);
    }
    r.nonFinite = nonFinitePixels(candidate);
    if (r.nonFinite > 0) {
        const size_t at = size_t(std::find_if(candidate.pixels.begin(), candidate.pixels.end(),
                                              [](float v) { return !std::isfinite(v); }) -
                                 candidate.pixels.begin()) / candidate.channels;
        r.firstNonFiniteX = int(at % candidate.width);
        r.firstNonFiniteY = int(at / candidate.width);
    }
    const bool anyNonFinite = r.nonFinite > 0 || nonFinitePixels(baseline) > 0;

    const Sums s = anyNonFinite ? compareWithNonFinite(baseline, candidate, options.threshold)
                                : sums(baseline, candidate, options.threshold);
    r.maxAbs = s.maxAbs;
    r.meanAbs = s.meanAbs;
    r.rmse = s.rmse;
    r.worstX = s.worstX;
    r.worstY = s.worstY;
    r.psnr = r.rmse > 0 ? -20.0 * std::log10(r.rmse) : kInf;   // 20 log10(1 / rmse)
    r.overThresholdShare = double(s.overThreshold) / (double(baseline.width) * baseline.height);

    const HostImage fa = anyNonFinite ? finiteCopy(baseline) : HostImage{};
    const HostImage fb = anyNonFinite ? finiteCopy(candidate) : HostImage{};
    const HostImage& a = anyNonFinite ? fa : baseline;
    const HostImage& b = anyNonFinite ? fb : candidate;
    r.ssim = ssim(a, b);
    if (options.flip) {
        CAVITY_ASSIGN(const flip::FlipResult f, flip::ldrFlip(a, b));
        r.flipMean = f.mean;
    }
    return r;
}

// A diverging map with a dark centre: no change is near black, and the
// colour gets lighter with the size of the change, blue where the new image
// is darker and orange where it is lighter, so a change's size reads as
// lightness in grey too and its sign as hue. The stops rise in CIE L* about
// evenly on each side.
std::array<float, 3> diffColor(double s) {
    static constexpr float darker[][3] = {
        {0.060f, 0.060f, 0.070f}, {0.090f, 0.200f, 0.420f}, {0.160f, 0.420f, 0.780f}, {0.560f, 0.780f, 1.000f}};
    static constexpr float lighter[][3] = {
        {0.060f, 0.060f, 0.070f}, {0.420f, 0.160f, 0.060f}, {0.820f, 0.400f, 0.100f}, {1.000f, 0.800f, 0.540f}};
    if (std::isnan(s)) return {1.0f, 0.0f, 1.0f};
    const auto& stops = s < 0 ? darker : lighter;
    constexpr int last = int(std::size(darker)) - 1;
    const double t = std::min(std::fabs(s), 1.0) * last;
    const int i = std::min(int(t), last - 1);
    const float u = float(t - i);
    std::array<float, 3> c{};
    for (int k = 0; k < 3; ++k) c[k] = stops[i][k] + u * (stops[i + 1][k] - stops[i][k]);
    return c;
}

HostImage heatmap(const HostImage& baseline, const HostImage& candidate, double scale) {
    HostImage out(candidate.width, candidate.height, 3);
    const int ch = std::min(baseline.channels, candidate.channels);
    for (int y = 0; y < candidate.height; ++y)
        for (int x = 0; x < candidate.width; ++x) {
            double signedErr = NAN;
            if (x < baseline.width && y < baseline.height && ch > 0) {
                signedErr = 0;
                for (int c = 0; c < ch; ++c) {
                    const float a = baseline.at(x, y, c), b = candidate.at(x, y, c);
                    if (sameNonFinite(a, b)) continue;   // as compare() counts them
                    const double d = double(b) - a;
                    if (std::isnan(d)) {
                        signedErr = NAN;
                        break;
                    }
                    if (std::fabs(d) > std::fabs(signedErr)) signedErr = d;
                }
            }
            const double s = std::isnan(signedErr) ? NAN : signedErr == 0 ? 0.0 : scale > 0 ? signedErr / scale : signedErr;
            const auto col = diffColor(s);
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = col[c];
        }
    return out;
}

}  // namespace cavity::images::metrics
