// Image metrics (metrics.h), LDR-FLIP (flip.h) and the Mann-Whitney U test
// (mann_whitney.h). CPU only. Expected values come from the definitions,
// by arithmetic stated next to them, never from the code under test.
#include "flip.h"
#include "mann_whitney.h"
#include "metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace cavity {
namespace {

// A deterministic pseudo-random value in [0, 1) (a 32-bit LCG).
struct Lcg {
    uint32_t s;
    explicit Lcg(uint32_t seed) : s(seed) {}
    float next() {
        s = s * 1664525u + 1013904223u;
        return float(s >> 8) / float(1u << 24);
    }
};

// A smooth test pattern in [0.2, 0.8] with some structure for SSIM and FLIP.
HostImage pattern(int w, int h, int c) {
    HostImage img(w, h, c);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < c; ++k)
                img.at(x, y, k) = 0.5f + 0.3f * float(std::sin(0.3 * x + 0.7 * k) * std::cos(0.2 * y));
    return img;
}

HostImage withNoise(const HostImage& img, float amplitude, uint32_t seed) {
    HostImage out = img;
    Lcg rng(seed);
    for (float& v : out.pixels) v += amplitude * (2 * rng.next() - 1);
    return out;
}

// ---- metrics::compare ----

TEST(Metrics, IdenticalImages) {
    const HostImage a = pattern(40, 30, 3);
    auto r = metrics::compare(a, a);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->maxAbs, 0.0);
    EXPECT_EQ(r->meanAbs, 0.0);
    EXPECT_EQ(r->rmse, 0.0);
    EXPECT_TRUE(std::isinf(r->psnr) && r->psnr > 0);
    EXPECT_EQ(r->overThresholdShare, 0.0);
    EXPECT_EQ(r->ssim, 1.0);
    EXPECT_EQ(r->nonFinite, 0);
    EXPECT_EQ(r->firstNonFiniteX, -1);
    EXPECT_EQ(r->flipMean, -1.0);   // not asked for
}

// Dyadic values keep float arithmetic exact: 8 of the 16 pixels are off by
// 1/8, one by 1/2, the rest equal. Then maxAbs = 1/2, meanAbs = (8/8 + 1/2)
// / 16 = 0.09375, rmse = sqrt((8/64 + 1/4) / 16) = sqrt(0.0234375).
TEST(Metrics, KnownOffsetGivesExactNumbers) {
    HostImage a(4, 4, 1, 0.25f), b = a;
    for (int i = 0; i < 8; ++i) b.pixels[size_t(i)] += 0.125f;
    b.at(2, 3) = 0.75f;
    auto r = metrics::compare(a, b);
    ASSERT_TRUE(r.ok()) << r.error().message;
    const double rmse = std::sqrt((8 * 0.125 * 0.125 + 0.5 * 0.5) / 16);
    EXPECT_DOUBLE_EQ(r->maxAbs, 0.5);
    EXPECT_EQ(r->worstX, 2);
    EXPECT_EQ(r->worstY, 3);
    EXPECT_DOUBLE_EQ(r->meanAbs, 0.09375);
    EXPECT_DOUBLE_EQ(r->rmse, rmse);
    EXPECT_NEAR(r->psnr, 20 * std::log10(1 / rmse), 1e-9);
    EXPECT_DOUBLE_EQ(r->overThresholdShare, 9.0 / 16);
}

// The mean is over values, not pixels: one of 2x1x3 = 6 values off by 0.5.
TEST(Metrics, MeanIsOverAllChannelValues) {
    HostImage a(2, 1, 3, 0.5f), b = a;
    b.at(1, 0, 2) = 1.0f;
    auto r = metrics::compare(a, b);
    ASSERT_TRUE(r.ok());
    EXPECT_DOUBLE_EQ(r->meanAbs, 0.5 / 6);
    EXPECT_DOUBLE_EQ(r->rmse, std::sqrt(0.25 / 6));
    EXPECT_EQ(r->worstX, 1);
    EXPECT_DOUBLE_EQ(r->overThresholdShare, 0.5);
}

// A constant alpha is not a colour channel: RGBA with alpha 1 in both images
// scores as its RGB would (the mean of 1/3 values off, not 1/4), and SSIM too.
TEST(Metrics, ConstantAlphaIsLeftOutButVaryingAlphaCounts) {
    HostImage rgb(8, 8, 3, 0.5f), rgbNew = rgb;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) rgbNew.at(x, y, 0) = 0.5f + 0.0625f * float((x + y) % 2);
    HostImage rgba(8, 8, 4, 1.0f), rgbaNew = rgba;
    for (size_t p = 0; p < 64; ++p)
        for (size_t c = 0; c < 3; ++c) {
            rgba.pixels[p * 4 + c] = rgb.pixels[p * 3 + c];
            rgbaNew.pixels[p * 4 + c] = rgbNew.pixels[p * 3 + c];
        }
    auto a = metrics::compare(rgb, rgbNew), b = metrics::compare(rgba, rgbaNew);
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_EQ(b->channelsCompared, 3);
    EXPECT_DOUBLE_EQ(b->meanAbs, a->meanAbs);
    EXPECT_DOUBLE_EQ(b->rmse, a->rmse);
    EXPECT_DOUBLE_EQ(b->ssim, a->ssim);
    rgbaNew.at(0, 0, 3) = 0.5f;   // alpha that varies is compared
    auto c = metrics::compare(rgba, rgbaNew);
    ASSERT_TRUE(c.ok());
    EXPECT_EQ(c->channelsCompared, 4);
}

// 8-bit images count the pixels that differ at all, or by more than a delta.
TEST(Metrics, DifferingPixelsCountOneStepChanges) {
    HostImage a(10, 10, 3, 100.0f / 255), b = a;
    for (int x = 0; x < 10; ++x) b.at(x, 0, 1) = 101.0f / 255;   // row 0: one step
    b.at(3, 5, 2) = 103.0f / 255;                                // one pixel: three steps
    metrics::Options o;
    o.eightBit = true;
    auto r = metrics::compare(a, b, o);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->differingPixels, 11);
    EXPECT_DOUBLE_EQ(r->differingShare, 0.11);
    o.differingDelta = 1;
    EXPECT_EQ(metrics::compare(a, b, o)->differingPixels, 1);
    o.differingDelta = 3;
    EXPECT_EQ(metrics::compare(a, b, o)->differingPixels, 0);
    EXPECT_EQ(metrics::compare(a, b)->differingPixels, 0) << "float images do not count";
}

// PSNR is for a signal range of 1.0 even when values exceed 1 (OIIO's own
// PSNR would use the largest value as the peak: 20 log10(2.5 / 0.5) = 14 dB).
TEST(Metrics, PsnrUsesUnitRange) {
    HostImage a(3, 3, 1, 2.0f), b(3, 3, 1, 2.5f);
    auto r = metrics::compare(a, b);
    ASSERT_TRUE(r.ok());
    EXPECT_NEAR(r->psnr, 20 * std::log10(1 / 0.5), 1e-9);   // 6.02 dB
}

// Threshold 0.1 on a 4x2 RGB image: pixel (0,0) one channel over, pixel
// (1,0) two channels over (counted once), pixel (2,0) under, pixel (3,1) over
// by a negative difference: 3 of 8 pixels.
TEST(Metrics, OverThresholdShareCountsPixels) {
    HostImage a(4, 2, 3, 0.5f), b = a;
    b.at(0, 0, 2) = 0.7f;
    b.at(1, 0, 0) = 0.8f;
    b.at(1, 0, 1) = 0.2f;
    b.at(2, 0, 1) = 0.55f;
    b.at(3, 1, 0) = 0.25f;
    metrics::Options o;
    o.threshold = 0.1;
    auto r = metrics::compare(a, b, o);
    ASSERT_TRUE(r.ok());
    EXPECT_DOUBLE_EQ(r->overThresholdShare, 3.0 / 8);
    o.threshold = 0.4;   // nothing differs by more than 0.3
    EXPECT_DOUBLE_EQ(metrics::compare(a, b, o)->overThresholdShare, 0.0);
}

TEST(Metrics, NanPixelIsCountedAndLocated) {
    HostImage a(8, 5, 1, 0.5f), b = a;
    b.at(3, 2) = std::numeric_limits<float>::quiet_NaN();
    auto r = metrics::compare(a, b);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->nonFinite, 1);
    EXPECT_EQ(r->firstNonFiniteX, 3);
    EXPECT_EQ(r->firstNonFiniteY, 2);
    // A NaN must fail every "<= tolerance" check, never slip through as NaN.
    EXPECT_TRUE(std::isinf(r->maxAbs));
    EXPECT_EQ(r->worstX, 3);
    EXPECT_EQ(r->worstY, 2);
    EXPECT_EQ(r->meanAbs, 0.0);   // the other 39 pixels are equal
    EXPECT_DOUBLE_EQ(r->overThresholdShare, 1.0 / 40);
    EXPECT_FALSE(std::isnan(r->ssim));
    EXPECT_LT(r->ssim, 1.0);
}

// Non-finite pixels are counted per pixel and the first is in row-major order.
TEST(Metrics, NonFiniteCountIsPerPixelRowMajor) {
    HostImage a(6, 4, 3, 0.5f), b = a;
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    b.at(2, 3, 0) = nan;
    b.at(5, 1, 1) = inf;
    b.at(5, 1, 2) = nan;   // same pixel as the Inf
    b.at(0, 2, 0) = 0.9f;  // a finite difference elsewhere: 0.4 in 1 of the 69 finite values
    auto r = metrics::compare(a, b);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->nonFinite, 2);
    EXPECT_EQ(r->firstNonFiniteX, 5);
    EXPECT_EQ(r->firstNonFiniteY, 1);
    EXPECT_TRUE(std::isinf(r->maxAbs));
    EXPECT_EQ(r->worstX, 5);
    EXPECT_EQ(r->worstY, 1);
    EXPECT_NEAR(r->meanAbs, 0.4 / 69, 1e-7);
    EXPECT_DOUBLE_EQ(r->overThresholdShare, 3.0 / 24);
}

TEST(Metrics, ShapeMismatchIsBadInput) {
    auto r = metrics::compare(HostImage(320, 180, 1), HostImage(160, 90, 1));
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, ErrorCode::BadInput);
    EXPECT_NE(r.error().message.find("baseline is 320x180x1, new image is 160x90x1"), std::string::npos)
        << r.error().message;
    auto c = metrics::compare(HostImage(8, 8, 1), HostImage(8, 8, 4));
    ASSERT_FALSE(c.ok());
    EXPECT_EQ(c.error().code, ErrorCode::BadInput);
}

TEST(Metrics, SsimIsOneForIdenticalAndDropsWithNoise) {
    const HostImage a = pattern(64, 48, 1);
    EXPECT_EQ(metrics::ssim(a, a), 1.0);
    const double noisy = metrics::ssim(a, withNoise(a, 0.2f, 7));
    EXPECT_LT(noisy, 0.9);
    EXPECT_GT(noisy, 0.0);
    // Less noise, more similar.
    EXPECT_GT(metrics::ssim(a, withNoise(a, 0.02f, 7)), noisy);
    auto r = metrics::compare(a, withNoise(a, 0.2f, 7));
    ASSERT_TRUE(r.ok());
    EXPECT_DOUBLE_EQ(r->ssim, noisy);
}

// Two constant images have no variance, so SSIM is the luminance term alone:
// (2 ua ub + C1) / (ua^2 + ub^2 + C1) with C1 = 0.01^2.
TEST(Metrics, SsimOfConstantImagesIsTheLuminanceTerm) {
    const double C1 = 1e-4, ua = 0.5, ub = 0.625;
    const double expected = (2 * ua * ub + C1) / (ua * ua + ub * ub + C1);
    EXPECT_NEAR(metrics::ssim(HostImage(20, 16, 2, 0.5f), HostImage(20, 16, 2, 0.625f)), expected, 1e-9);
    // Smaller than the 11x11 window: still defined.
    EXPECT_NEAR(metrics::ssim(HostImage(5, 3, 1, 0.5f), HostImage(5, 3, 1, 0.625f)), expected, 1e-9);
}

// ---- heat-map ----

TEST(Heatmap, RgbWithFirstColourForNoError) {
    HostImage a(10, 6, 1, 0.5f), b = a;
    b.at(7, 2) = 0.6f;   // error 0.1 = scale: top of the map
    b.at(1, 4) = 0.55f;  // half the scale
    const HostImage h = metrics::heatmap(a, b, 0.1);
    ASSERT_EQ(h.width, 10);
    ASSERT_EQ(h.height, 6);
    ASSERT_EQ(h.channels, 3);
    const auto first = metrics::heatColor(0), top = metrics::heatColor(1);
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(h.at(0, 0, c), first[c]);
        EXPECT_EQ(h.at(9, 5, c), first[c]);
        EXPECT_NEAR(h.at(7, 2, c), top[c], 1e-5);
    }
    // More error, brighter.
    auto luma = [&](int x, int y) { return 0.2126 * h.at(x, y, 0) + 0.7152 * h.at(x, y, 1) + 0.0722 * h.at(x, y, 2); };
    EXPECT_LT(luma(0, 0), luma(1, 4));
    EXPECT_LT(luma(1, 4), luma(7, 2));
}

TEST(Heatmap, ColourMapRisesInLightness) {
    double previous = -1;
    for (int i = 0; i <= 64; ++i) {
        const auto c = metrics::heatColor(i / 64.0);
        for (float v : c) {
            EXPECT_GE(v, 0.0f);
            EXPECT_LE(v, 1.0f);
        }
        const double luma = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        EXPECT_GT(luma, previous) << "at " << i / 64.0;
        previous = luma;
    }
    EXPECT_EQ(metrics::heatColor(-3)[0], metrics::heatColor(0)[0]);
    EXPECT_EQ(metrics::heatColor(7)[1], metrics::heatColor(1)[1]);
}

TEST(Heatmap, NanIsTopColourUnlessInBoth) {
    HostImage a(3, 3, 1, 0.5f), b = a;
    b.at(1, 1) = std::numeric_limits<float>::quiet_NaN();
    b.at(2, 2) = a.at(2, 2) = std::numeric_limits<float>::quiet_NaN();   // NaN in both: equal, as compare() counts it
    const HostImage h = metrics::heatmap(a, b, 0.5);
    EXPECT_EQ(h.at(1, 1, 1), metrics::heatColor(1)[1]);
    EXPECT_EQ(h.at(2, 2, 1), metrics::heatColor(0)[1]);
}

// ---- FLIP ----

TEST(Flip, IdenticalImagesGiveZero) {
    const HostImage a = pattern(48, 32, 3);
    auto f = flip::ldrFlip(a, a);
    ASSERT_TRUE(f.ok()) << f.error().message;
    EXPECT_EQ(f->mean, 0.0);
    for (float v : f->errorMap.pixels) ASSERT_EQ(v, 0.0f);
}

TEST(Flip, ErrorMapHasTheInputSize) {
    const HostImage a = pattern(37, 23, 4), b = withNoise(a, 0.05f, 3);
    auto f = flip::ldrFlip(a, b);
    ASSERT_TRUE(f.ok()) << f.error().message;
    EXPECT_EQ(f->errorMap.width, 37);
    EXPECT_EQ(f->errorMap.height, 23);
    EXPECT_EQ(f->errorMap.channels, 1);
    double sum = 0;
    for (float v : f->errorMap.pixels) {
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 1.0f);
        sum += v;
    }
    EXPECT_NEAR(f->mean, sum / (37 * 23), 1e-6);
    EXPECT_GT(f->mean, 0.0);
}

TEST(Flip, ErrorGrowsWithOffset) {
    const HostImage a = pattern(40, 40, 1);
    double previous = 0;
    for (float offset : {0.01f, 0.03f, 0.06f, 0.1f, 0.15f, 0.2f}) {
        HostImage b = a;
        for (float& v : b.pixels) v += offset;
        auto f = flip::ldrFlip(a, b);
        ASSERT_TRUE(f.ok());
        EXPECT_GT(f->mean, previous) << "offset " << offset;
        previous = f->mean;
    }
}

// Black against white: HyAB 100 in L*, 100^0.7 = 25.1, above pc * cmax, so
// 0.95 + (25.1 - pc cmax) / (cmax - pc cmax) * 0.05 with cmax = 203.4^0.7 =
// 41.3 (Hunt-adjusted green vs blue): about 0.967, everywhere (no features).
TEST(Flip, BlackVersusWhiteIsNearOne) {
    auto f = flip::ldrFlip(HostImage(32, 32, 3, 0.0f), HostImage(32, 32, 3, 1.0f));
    ASSERT_TRUE(f.ok());
    EXPECT_GT(f->mean, 0.95);
    EXPECT_LE(f->mean, 1.0);
    EXPECT_NEAR(f->mean, 0.967, 0.003);
    // Grey input is replicated to RGB: the same answer from 1 channel.
    auto g = flip::ldrFlip(HostImage(32, 32, 1, 0.0f), HostImage(32, 32, 1, 1.0f));
    ASSERT_TRUE(g.ok());
    EXPECT_NEAR(g->mean, f->mean, 1e-9);
}

// The filters reach 10 pixels (contrast sensitivity) and 9 pixels (features)
// at 67 pixels per degree: beyond that a one-pixel change leaves no error.
TEST(Flip, OnePixelDifferenceIsLocal) {
    HostImage a = pattern(64, 64, 3), b = a;
    for (int c = 0; c < 3; ++c) b.at(30, 20, c) = 1.0f - a.at(30, 20, c);
    auto f = flip::ldrFlip(a, b);
    ASSERT_TRUE(f.ok());
    EXPECT_GT(f->errorMap.at(30, 20), 0.05f);
    int nonzero = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const bool far = std::abs(x - 30) > 10 || std::abs(y - 20) > 10;
            if (far) {
                EXPECT_EQ(f->errorMap.at(x, y), 0.0f) << "at " << x << "," << y;
            }
            nonzero += f->errorMap.at(x, y) > 0;
        }
    EXPECT_GT(nonzero, 1);   // the error spreads a little, as the eye blurs it
}

// Pinned against a plain-Python port of NVIDIA's reference flip.py (LDR
// path, written with full 2D kernels rather than our separable ones): on
// these two 26x21 image pairs at the default 67.02 PPD it gives means of
// 0.173185613 (smooth colours, noise on the right, a bright row) and
// 0.638748381 (saturated stripes, which leave the RGB cube when filtered);
// its per-pixel maps agree with ours to 2e-6.
TEST(Flip, MatchesTheReferenceImplementation) {
    const int w = 26, h = 21;
    HostImage a(w, h, 3), b(w, h, 3), c(w, h, 3), d(w, h, 3);
    uint32_t s = 12345;
    auto rnd = [&] {
        s = s * 1664525u + 1013904223u;
        return float(s >> 8) / float(1u << 24);
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < 3; ++k) {
                a.at(x, y, k) = 0.5f + 0.4f * float(std::sin(0.5 * x + 1.1 * k) * std::cos(0.35 * y - 0.4 * k));
                b.at(x, y, k) = a.at(x, y, k) + (x > 12 ? 0.15f * (rnd() - 0.3f) : 0.0f) + (y == 5 ? 0.3f : 0.0f);
                c.at(x, y, k) = (x / 3 + y / 4) % 3 == k ? 1.0f : 0.0f;
                d.at(x, y, k) = (x / 3 + y / 5) % 3 == k ? 1.0f : 0.05f;
            }
    const double ppd = flip::pixelsPerDegree(0.7, 0.7, 3840);
    auto smooth = flip::ldrFlip(a, b, ppd);
    ASSERT_TRUE(smooth.ok());
    EXPECT_NEAR(smooth->mean, 0.173185613, 1e-6);
    auto stripes = flip::ldrFlip(c, d, ppd);
    ASSERT_TRUE(stripes.ok());
    EXPECT_NEAR(stripes->mean, 0.638748381, 1e-6);
}

TEST(Flip, BadShapesAreBadInput) {
    auto f = flip::ldrFlip(HostImage(8, 8, 3), HostImage(8, 4, 3));
    ASSERT_FALSE(f.ok());
    EXPECT_EQ(f.error().code, ErrorCode::BadInput);
    auto g = flip::ldrFlip(HostImage(8, 8, 2), HostImage(8, 8, 2));
    ASSERT_FALSE(g.ok());
    EXPECT_EQ(g.error().code, ErrorCode::BadInput);
}

TEST(Flip, DefaultViewingConditions) {
    EXPECT_NEAR(flip::pixelsPerDegree(0.7, 0.7, 3840), 67.02, 0.01);
}

TEST(Flip, CompareFillsFlipMeanWhenAsked) {
    const HostImage a = pattern(32, 24, 4), b = withNoise(a, 0.1f, 11);
    metrics::Options o;
    o.flip = true;
    auto r = metrics::compare(a, b, o);
    ASSERT_TRUE(r.ok()) << r.error().message;
    auto f = flip::ldrFlip(a, b);
    ASSERT_TRUE(f.ok());
    EXPECT_EQ(r->flipMean, f->mean);
    EXPECT_GT(r->flipMean, 0.0);
    auto same = metrics::compare(a, a, o);
    ASSERT_TRUE(same.ok());
    EXPECT_EQ(same->flipMean, 0.0);
}

// ---- Mann-Whitney U ----
// Expected values from this Python (no scipy), written apart from the C++:
// U by counting pairs, the normal approximation from the textbook formula,
// the exact p by enumerating every split of the pooled sample.
//
//   def u_pairs(a, b): return sum((x > y) + 0.5 * (x == y) for x in a for y in b)
//   def asym(a, b):
//       n1, n2 = len(a), len(b); n = n1 + n2; u1 = u_pairs(a, b); u = max(u1, n1*n2 - u1)
//       p = a + b; ties = sum(p.count(v)**3 - p.count(v) for v in set(p))
//       z = (u - n1*n2/2 - 0.5) / math.sqrt(n1*n2/12 * ((n+1) - ties/(n*(n-1))))
//       return u1, min(1.0, math.erfc(z / math.sqrt(2)))
//   def exact(a, b):
//       p = a + b; u1 = u_pairs(a, b); u = max(u1, len(a)*len(b) - u1); hit = tot = 0
//       for idx in itertools.combinations(range(len(p)), len(a)):
//           rest = [p[i] for i in range(len(p)) if i not in idx]
//           tot += 1; hit += u_pairs([p[i] for i in idx], rest) >= u
//       return u1, min(1.0, 2 * hit / tot)
//
// The first case is also scipy's: mannwhitneyu([1..5], [6..10]) gives
// p = 2/252 (exact) and 0.0121858 with method='asymptotic'.

TEST(MannWhitney, SeparatedSmallSamples) {
    const std::vector<double> a{1, 2, 3, 4, 5}, b{6, 7, 8, 9, 10};
    const auto asym = stats::mannWhitneyUAsymptotic(a, b);
    EXPECT_EQ(asym.u, 0.0);
    EXPECT_NEAR(asym.p, 0.0121857803553448, 1e-12);
    const auto exact = stats::mannWhitneyUExact(a, b);
    EXPECT_EQ(exact.u, 0.0);
    EXPECT_NEAR(exact.p, 2.0 / 252, 1e-15);
    const auto chosen = stats::mannWhitneyU(a, b);   // small, no ties: exact
    EXPECT_TRUE(chosen.exact);
    EXPECT_NEAR(chosen.p, 2.0 / 252, 1e-15);
    // Swapping the samples mirrors U and keeps p.
    const auto swapped = stats::mannWhitneyU(b, a);
    EXPECT_EQ(swapped.u, 25.0);
    EXPECT_NEAR(swapped.p, chosen.p, 1e-15);
}

TEST(MannWhitney, TiesUseTheCorrectedNormalApproximation) {
    const std::vector<double> a{1, 2, 2, 3, 4, 7}, b{2, 3, 4, 5, 5, 6, 8};
    const auto r = stats::mannWhitneyU(a, b);
    EXPECT_FALSE(r.exact);
    EXPECT_EQ(r.u, 11.0);
    EXPECT_NEAR(r.p, 0.170567192255758, 1e-12);
}

TEST(MannWhitney, InterleavedSamples) {
    const std::vector<double> a{0.8, 1.3, 2.2, 2.9, 3.1, 4.4, 5.0}, b{1.1, 1.7, 3.6, 3.9, 4.8, 5.5, 6.1, 7.2};
    EXPECT_EQ(stats::mannWhitneyU(a, b).u, 16.0);
    EXPECT_NEAR(stats::mannWhitneyUAsymptotic(a, b).p, 0.183232976928822, 1e-12);
    EXPECT_NEAR(stats::mannWhitneyUExact(a, b).p, 0.189277389277389, 1e-12);
}

TEST(MannWhitney, IdenticalSamplesGivePOne) {
    const std::vector<double> a{3.1, 2.7, 3.3, 2.9, 3.0, 3.2, 2.8, 3.4, 3.05, 2.95};
    const auto r = stats::mannWhitneyU(a, a);
    EXPECT_EQ(r.p, 1.0);
    EXPECT_EQ(r.u, 50.0);   // n1 n2 / 2
    EXPECT_EQ(stats::mannWhitneyU({1, 1, 1}, {1, 1, 1}).p, 1.0);   // all tied: no variance
    EXPECT_EQ(stats::mannWhitneyU({}, {1, 2}).p, 1.0);
}

TEST(MannWhitney, ShiftedLargeSamplesAreSignificant) {
    Lcg rng(42);
    std::vector<double> a, b;
    for (int i = 0; i < 200; ++i) {
        a.push_back(1.0 + 0.2 * rng.next());   // frame times around 1.1 ms
        b.push_back(1.1 + 0.2 * rng.next());   // 0.1 ms slower
    }
    const auto r = stats::mannWhitneyU(a, b);
    EXPECT_FALSE(r.exact);
    EXPECT_LT(r.p, 1e-6);
    // Same distribution, different draws: not significant.
    std::vector<double> c;
    for (int i = 0; i < 200; ++i) c.push_back(1.0 + 0.2 * rng.next());
    EXPECT_GT(stats::mannWhitneyU(a, c).p, 0.001);
}

}  // namespace
}  // namespace cavity
