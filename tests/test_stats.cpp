// Statistics and configuration ids: plain functions, no GPU.
#include "config.h"
#include "stats.h"
#include "timing.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cavity {
namespace {

TEST(Stats, SummarizesAKnownSample) {
    const Stats s = summarize({4, 1, 3, 2, 5});
    EXPECT_EQ(s.count, 5);
    EXPECT_DOUBLE_EQ(s.median, 3);
    EXPECT_DOUBLE_EQ(s.min, 1);
    EXPECT_DOUBLE_EQ(s.max, 5);
    EXPECT_DOUBLE_EQ(s.mean, 3);
    EXPECT_NEAR(s.p90, 4.6, 1e-12);            // rank 3.6 between 4 and 5
    EXPECT_NEAR(s.stddev, std::sqrt(2.5), 1e-12);
    EXPECT_NEAR(s.cv, std::sqrt(2.5) / 3, 1e-12);
}

TEST(ClockCheck, RejectsTimersThatMissTheWork) {
    const ClockCheck c;
    // llvmpipe GL, measured (../shared/docs/GPU.md): 0.06 ms between the
    // timestamps of a pass whose drained wall time is 48.8 ms.
    EXPECT_FALSE(c.trusted(0.06, 48.8));
    EXPECT_FALSE(c.trusted(0.0, 1.0));
    EXPECT_FALSE(c.trusted(10.0, 5.0));        // more GPU time than wall time
    // H100: timestamps within 6% of the wall clock; tiny frames within the
    // fixed submission overhead.
    EXPECT_TRUE(c.trusted(0.339, 0.351));
    EXPECT_TRUE(c.trusted(0.05, 0.2));
}

TEST(ConfigId, IsTheCanonicalPath) {
    RunConfig c;
    ASSERT_TRUE(setParam(c, "scene", "slats").ok());
    ASSERT_TRUE(setParam(c, "samples", "32").ok());
    ASSERT_TRUE(setParam(c, "blur", "2").ok());
    c.half = true;
    c.api = gpu::Api::OpenGL;
    c.stage = gpu::Stage::Fragment;
    EXPECT_EQ(configId(c), "slats/alchemy/n32/b2/half/320x180/gl/fragment");
}

TEST(ConfigValidation, NamesFlagValueAndRange) {
    RunConfig c;
    ASSERT_TRUE(setParam(c, "samples", "300").ok());
    const Status s = validate(c);
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().code, ErrorCode::BadInput);
    EXPECT_EQ(s.error().message, "--samples 300: must be an integer in 1..256 (samples)");
}

}  // namespace
}  // namespace cavity
