// Image metrics (metrics.h): the comparison numbers and the heat-map.
// Expected values come from the definitions, by arithmetic stated next to
// them, never from the code under test. CPU only.
#include "harness_names.h"
#include "images/metrics.h"
#include "image_patterns.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace cavity {

using namespace cavity::harness;
namespace {

using test::Lcg;
using test::pattern;
using test::withNoise;

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

TEST(Heatmap, SignedAndSaturatingAtTheScale) {
    HostImage a(10, 6, 1, 0.5f), b = a;
    b.at(7, 2) = 0.6f;   // lighter by the scale: top of the lighter side
    b.at(1, 4) = 0.55f;  // lighter by half the scale
    b.at(3, 3) = 0.4f;   // darker by the scale
    b.at(4, 3) = 0.1f;   // darker by four times the scale: clamped
    const HostImage h = metrics::heatmap(a, b, 0.1);
    ASSERT_EQ(h.width, 10);
    ASSERT_EQ(h.height, 6);
    ASSERT_EQ(h.channels, 3);
    const auto none = metrics::diffColor(0), lighter = metrics::diffColor(1), darker = metrics::diffColor(-1);
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(h.at(0, 0, c), none[c]);
        EXPECT_EQ(h.at(9, 5, c), none[c]);
        EXPECT_NEAR(h.at(7, 2, c), lighter[c], 1e-5);
        EXPECT_NEAR(h.at(3, 3, c), darker[c], 1e-5);
        EXPECT_NEAR(h.at(4, 3, c), darker[c], 1e-5);
    }
    // More change, lighter; lighter pixels lean red, darker ones blue.
    auto luma = [&](int x, int y) { return 0.2126 * h.at(x, y, 0) + 0.7152 * h.at(x, y, 1) + 0.0722 * h.at(x, y, 2); };
    EXPECT_LT(luma(0, 0), luma(1, 4));
    EXPECT_LT(luma(1, 4), luma(7, 2));
    EXPECT_GT(h.at(7, 2, 0), h.at(7, 2, 2));
    EXPECT_GT(h.at(3, 3, 2), h.at(3, 3, 0));
}

TEST(Heatmap, TakesTheSignOfTheChannelThatMovedMost) {
    HostImage a(2, 1, 3, 0.5f), b = a;
    b.at(0, 0, 0) = 0.52f;
    b.at(0, 0, 2) = 0.45f;   // the larger move, darker
    const HostImage h = metrics::heatmap(a, b, 0.1);
    const auto want = metrics::diffColor(-0.5);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(h.at(0, 0, c), want[c], 1e-5);
}

TEST(Heatmap, ColourMapRisesInLightnessOnBothSides) {
    for (const double sign : {-1.0, 1.0}) {
        double previous = -1;
        for (int i = 0; i <= 64; ++i) {
            const auto c = metrics::diffColor(sign * i / 64.0);
            for (float v : c) {
                EXPECT_GE(v, 0.0f);
                EXPECT_LE(v, 1.0f);
            }
            const double luma = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
            EXPECT_GT(luma, previous) << "at " << sign * i / 64.0;
            previous = luma;
        }
    }
    EXPECT_EQ(metrics::diffColor(-3)[2], metrics::diffColor(-1)[2]);
    EXPECT_EQ(metrics::diffColor(7)[1], metrics::diffColor(1)[1]);
}

TEST(Heatmap, NanIsMagentaUnlessInBoth) {
    HostImage a(3, 3, 1, 0.5f), b = a;
    b.at(1, 1) = std::numeric_limits<float>::quiet_NaN();
    b.at(2, 2) = a.at(2, 2) = std::numeric_limits<float>::quiet_NaN();   // NaN in both: equal, as compare() counts it
    const HostImage h = metrics::heatmap(a, b, 0.5);
    EXPECT_EQ(h.at(1, 1, 0), 1.0f);
    EXPECT_EQ(h.at(1, 1, 1), 0.0f);
    EXPECT_EQ(h.at(2, 2, 1), metrics::diffColor(0)[1]);
}

}  // namespace
}  // namespace cavity
