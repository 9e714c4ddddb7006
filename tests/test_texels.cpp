// Texel conversions (backends/texels): Imath's half against GCC's own
// _Float16 conversion (libgcc's, an independent implementation), on every
// rounding boundary of every normal half and on every float that becomes a
// half denormal; UNORM8 as GPUs store it.
#include "harness_names.h"
#include "texels/texels.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

using namespace cavity::harness;

namespace {

using namespace cavity::gpu::texels;

uint16_t oracle(float f) { return std::bit_cast<uint16_t>(static_cast<_Float16>(f)); }
bool isHalfNan(uint16_t h) { return (h & 0x7c00u) == 0x7c00u && (h & 0x3ffu) != 0; }

TEST(Texels, HalfRoundsToNearestEvenOnEveryBoundary) {
    // Sign, exponent and the 10 mantissa bits a half keeps, times the 13
    // dropped bits just below, at and above the tie.
    const uint32_t dropped[] = {0, 1, 0xfff, 0x1000, 0x1001, 0x1fff};
    int checked = 0;
    for (uint32_t high = 0; high < (1u << 19); ++high)
        for (uint32_t low : dropped) {
            const uint32_t bits = high << 13 | low;
            const float f = std::bit_cast<float>(bits);
            const uint16_t h = toHalf(f);
            if (std::isnan(f)) {
                ASSERT_TRUE(isHalfNan(h)) << std::hex << bits;
                continue;
            }
            ASSERT_EQ(h, oracle(f)) << std::hex << "float bits " << bits;
            ++checked;
        }
    EXPECT_GT(checked, 3000000);
}

TEST(Texels, HalfDenormalsRoundToNearestEven) {
    // Every fifth float from 2^-26 (rounds to zero) up to the smallest normal
    // half, both signs: each pattern of dropped bits, ties included, recurs
    // across the range, so the stride still meets every one (and keeps the
    // test near a second).
    for (uint32_t bits = 0x32800000u; bits < 0x38800000u; bits += 5) {
        const float f = std::bit_cast<float>(bits);
        ASSERT_EQ(toHalf(f), oracle(f)) << std::hex << bits;
        ASSERT_EQ(toHalf(-f), oracle(-f)) << std::hex << bits;
    }
    EXPECT_EQ(toHalf(65519.0f), uint16_t(0x7bff));   // the largest half
    EXPECT_EQ(toHalf(65520.0f), uint16_t(0x7c00));   // the tie goes to the even neighbour: infinity
    EXPECT_EQ(toHalf(-INFINITY), uint16_t(0xfc00));
}

TEST(Texels, EveryHalfReadsBackExactly) {
    for (uint32_t h = 0; h < 0x10000u; ++h) {
        const float f = fromHalf(uint16_t(h));
        const float expected = static_cast<float>(std::bit_cast<_Float16>(uint16_t(h)));
        if (isHalfNan(uint16_t(h))) {
            EXPECT_TRUE(std::isnan(f)) << std::hex << h;
            continue;
        }
        ASSERT_EQ(std::bit_cast<uint32_t>(f), std::bit_cast<uint32_t>(expected)) << std::hex << h;
        EXPECT_EQ(toHalf(f), uint16_t(h)) << std::hex << h;
        EXPECT_EQ(std::bit_cast<uint32_t>(roundToHalf(f)), std::bit_cast<uint32_t>(f)) << std::hex << h;
    }
    EXPECT_EQ(roundToHalf(1.0f + 1.0f / 4096), 1.0f);   // below half an ulp (2^-11) of 1
    EXPECT_EQ(roundToHalf(1.0f + 3.0f / 2048), 1.0f + 2.0f / 1024);   // a tie: to even
}

TEST(Texels, Unorm8ClampsAndRoundsHalfUp) {
    for (int k = 0; k < 256; ++k) {
        EXPECT_EQ(toUnorm8(float(k) / 255.0f), k);
        EXPECT_EQ(fromUnorm8(uint8_t(k)), float(k) / 255.0f);
        EXPECT_EQ(roundToUnorm8(float(k) / 255.0f), float(k) / 255.0f);
    }
    EXPECT_EQ(toUnorm8(0.51f / 255.0f), 1);          // rounded, not truncated
    EXPECT_EQ(toUnorm8(0.49f / 255.0f), 0);
    EXPECT_EQ(toUnorm8(-1.0f), 0);
    EXPECT_EQ(toUnorm8(2.0f), 255);
    EXPECT_EQ(toUnorm8(NAN), 0);                      // as GPUs store NaN
    EXPECT_EQ(roundToUnorm8(NAN), 0.0f);
}

}  // namespace
