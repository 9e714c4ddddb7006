// LDR-FLIP (flip.h).
// Expected values come from the definitions, by arithmetic stated next to
// them, never from the code under test. CPU only.
#include "harness_names.h"
#include "images/flip.h"
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

}  // namespace
}  // namespace cavity
