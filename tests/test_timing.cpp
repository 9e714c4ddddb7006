// Timing sanity on both backends: no zero times, GPU time consistent with the
// drained wall clock where the GPU clock is used, and a pass with four times
// the pixels reporting at least twice the time (a timer that misses the work,
// like llvmpipe's GL timestamps, fails this unless the harness falls back).
#include "gpu_fixture.h"
#include "measure/timing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace cavity::test {
namespace {

class Timing : public GpuTest {
protected:
    RunConfig configAt(int w, int h) {
        RunConfig c;
        c.api = api();
        c.width = w;
        c.height = h;
        return c;
    }
    cavity::measure::Timing measureAt(int w, int h, int frames) {
        RunConfig c;
        c.api = api();
        c.width = w;
        c.height = h;
        auto chain = PassChain::create(gpu(), c);
        EXPECT_TRUE(chain) << chain.error().message;
        if (!chain) return {};
        TimingOptions o = defaultTimingOptions(gpu().info());
        o.warmup = 2;
        o.frames = frames;
        o.maxNoise = 0;
        auto t = measurePasses(gpu(), **chain, o);
        EXPECT_TRUE(t) << t.error().message;
        return t ? *t : cavity::measure::Timing{};
    }
};

TEST_P(Timing, EveryReportedTimeIsPositive) {
    const auto t = measureAt(160, 90, 5);
    ASSERT_FALSE(t.passes.empty());
    for (const auto& p : t.passes)
        for (double ms : p.ms) EXPECT_GT(ms, 0.0) << p.name << " on " << t.clock;
    for (double ms : t.frame.ms) EXPECT_GT(ms, 0.0);
}

// The clock is decided on the warm GPU: a timer that misreads while cold
// (the first check fails, as a first configuration's did on the H200) does
// not lock the measurement onto the wall clock.
TEST_P(Timing, AColdProbeThatFailsDoesNotDecideTheClock) {
    RunConfig c = configAt(160, 90);
    auto chain = PassChain::create(gpu(), c);
    ASSERT_TRUE(chain) << chain.error().message;
    TimingOptions o = defaultTimingOptions(gpu().info());
    o.warmup = 2;
    o.frames = 5;
    o.maxNoise = 0;
    // A timer that misreads while cold and reads right once warm, on
    // whatever renders here: the checks of a CPU renderer pass or fail by the
    // host's load (both APIs failed a warm check under a loaded ASan CI), so
    // the double decides them all.
    ClockCheck coldFails;
    coldFails.distrustFirst = 1;
    coldFails.trustRest = true;
    coldFails.coldCounts = false;   // the rule of a GPU
    auto t = measurePasses(gpu(), **chain, o, nullptr, coldFails);
    ASSERT_TRUE(t) << t.error().message;
    EXPECT_EQ(t->clock, "gpu-timestamp") << t->clockNote;
    EXPECT_NE(t->clockNote.find("cold probe"), std::string::npos) << t->clockNote;
    // A repetition told the first one used the wall clock decides again, and says so.
    o.clock = "wall";
    ClockCheck gpuRule;
    gpuRule.trustRest = true;
    gpuRule.coldCounts = false;
    auto rep = measurePasses(gpu(), **chain, o, nullptr, gpuRule);
    ASSERT_TRUE(rep) << rep.error().message;
    EXPECT_EQ(rep->clock, "gpu-timestamp");
    EXPECT_NE(rep->clockNote.find("re-decided"), std::string::npos) << rep->clockNote;
    // A warm check that fails once (a host hiccup during its drained
    // frames) is tried again and does not move the clock; one that fails
    // every time does. A failing check asks the timer once, and with no
    // warm-up frames (whose submissions are checked too) the cold probe
    // and the warm checks are all that ask.
    o.clock = "gpu-timestamp";
    o.warmup = 0;
    ClockCheck hiccup;
    hiccup.distrustFirst = 2;   // the cold probe and the first warm check
    hiccup.trustRest = true;
    hiccup.coldCounts = false;
    auto h = measurePasses(gpu(), **chain, o, nullptr, hiccup);
    ASSERT_TRUE(h) << h.error().message;
    EXPECT_EQ(h->clock, "gpu-timestamp") << h->clockNote;
    EXPECT_NE(h->clockNote.find("passed when tried again"), std::string::npos) << h->clockNote;
    ClockCheck broken = hiccup;
    broken.distrustFirst = 2 + kClockRetries;   // the cold probe and every warm check
    auto b = measurePasses(gpu(), **chain, o, nullptr, broken);
    ASSERT_TRUE(b) << b.error().message;
    EXPECT_EQ(b->clock, "wall") << b->clockNote;
    EXPECT_NE(b->clockNote.find("re-decided"), std::string::npos) << b->clockNote;
    // On a software renderer a cold failure keeps the wall clock (the default rule).
    if (gpu().info().softwareRenderer) {
        ClockCheck strict;
        strict.distrustFirst = 1;
        o.clock.reset();
        auto s = measurePasses(gpu(), **chain, o, nullptr, strict);
        ASSERT_TRUE(s) << s.error().message;
        EXPECT_EQ(s->clock, "wall") << s->clockNote;
    }
}

TEST_P(Timing, GpuClockIsUsedOnlyWhenItAgreesWithTheWallClock) {
    const auto t = measureAt(160, 90, 5);
    const ClockCheck check;
    ASSERT_EQ(t.frameGpu.ms.size(), t.frameWall.ms.size());
    if (t.clock == "gpu-timestamp") {
        // The harness checks each submission (a batch of frames, or one
        // drained frame) and leaves out the frames of one that fails. A kept
        // frame carries its batch's wall time shared out evenly, so one frame
        // may sit above its share while its batch agrees: the check holds for
        // what was kept taken together, within ClockCheck's tolerances: a
        // little over the wall time at most (plus a little a submission) and
        // covering at least half of it, or all but a fixed overhead a
        // submission. (Checking each frame against its
        // share failed 2 of 5 frames on llvmpipe under a parallel ctest.)
        ASSERT_GE(t.batchFrames, 1);
        double gpuMs = 0, wallMs = 0;
        for (size_t i = 0; i < t.frameGpu.ms.size(); ++i) {
            gpuMs += t.frameGpu.ms[i];
            wallMs += t.frameWall.ms[i];
        }
        const double submissions = std::ceil(double(t.frameGpu.ms.size()) / t.batchFrames);
        EXPECT_GT(gpuMs, 0.0);
        EXPECT_LE(gpuMs, wallMs * check.maxOverWall + check.slopMs * submissions)
            << "gpu " << gpuMs << " ms, wall " << wallMs << " ms over " << submissions << " submissions";
        EXPECT_TRUE(gpuMs >= check.minFraction * wallMs || wallMs - gpuMs <= check.overheadMs * submissions)
            << "gpu " << gpuMs << " ms, wall " << wallMs << " ms over " << submissions << " submissions";
    } else {
        EXPECT_EQ(t.clock, "wall");
        EXPECT_FALSE(t.clockNote.empty());
        // Either the frame or one pass timed alone disagreed with the wall clock.
        EXPECT_NE(t.clockNote.find("do not bracket"), std::string::npos) << t.clockNote;
    }
}

// The AO pass: per-pixel work dominates it, where the G-buffer march and
// the cheap composite carry fixed per-dispatch costs on a CPU. A CPU
// renderer shares its cores with the other tests of a parallel ctest, and
// load only ever adds time: so the two sizes are measured in turns, and each
// size's fastest median so far is what is compared, for up to five rounds.
// (One round of each failed once in CI: load made the smaller size read
// almost as long as the larger.)
TEST_P(Timing, FourTimesThePixelsTakesAtLeastTwiceTheTime) {
    auto aoMedian = [](const cavity::measure::Timing& t) {
        for (const auto& p : t.passes)
            if (p.name == "ao") return p.stats.median;
        ADD_FAILURE() << "no ao pass";
        return 0.0;
    };
    double small = std::numeric_limits<double>::infinity(), large = small;
    std::string clock;
    for (int round = 0; round < 5 && !(large >= 2.0 * small); ++round) {
        const auto s = measureAt(320, 180, 9), l = measureAt(640, 360, 9);
        small = std::min(small, aoMedian(s));
        large = std::min(large, aoMedian(l));
        clock = s.clock;
    }
    EXPECT_GE(large, 2.0 * small) << "ao on " << clock << ": 320x180 " << small << " ms, 640x360 " << large << " ms";
}

// Batched frames (many per submission) and drained frames (one each) run the
// same passes on the same inputs: the same images, bit for bit, and with a
// fixed count the same number of samples of every pass.
TEST_P(Timing, BatchedAndDrainedGiveTheSameImagesAndSampleCounts) {
    const RunConfig c = configAt(160, 90);
    auto chain = PassChain::create(gpu(), c);
    ASSERT_TRUE(chain) << chain.error().message;
    std::map<TimingMode, std::map<std::string, HostImage>> images;
    for (TimingMode mode : {TimingMode::Batch, TimingMode::Drained}) {
        TimingOptions o = defaultTimingOptions(gpu().info());
        o.mode = mode;
        o.warmup = 1;
        o.steadyWarmup = false;
        o.frames = 7;
        o.maxNoise = 0;
        o.batchMs = 1e6;   // the whole measurement in one submission where batched
        auto t = measurePasses(gpu(), **chain, o);
        ASSERT_TRUE(t) << t.error().message;
        EXPECT_EQ(t->frame.ms.size(), 7u) << timingModeName(mode);
        for (const auto& p : t->passes) EXPECT_EQ(p.ms.size(), 7u) << p.name << " " << timingModeName(mode);
        EXPECT_EQ(t->stop, "frames");
        if (t->clock == "gpu-timestamp") {
            EXPECT_EQ(t->mode, mode);
        } else {
            EXPECT_EQ(t->mode, TimingMode::Drained) << "the wall clock times passes alone";
        }
        if (t->clock == "gpu-timestamp" && mode == TimingMode::Batch) {
            EXPECT_GT(t->batchFrames, 1);
        }
        for (const auto& out : userOutputs(c)) {
            auto img = (*chain)->read(out.image);
            ASSERT_TRUE(img) << img.error().message;
            images[mode][out.image] = std::move(*img);
        }
    }
    for (const auto& [name, img] : images[TimingMode::Batch])
        EXPECT_TRUE(img.pixels == images[TimingMode::Drained][name].pixels) << name;
    EXPECT_TRUE(gpu().takeDebugMessages().empty());
}

// The pipeline recorded under one scope (cavity_bench's
// pipeline_one_scope_ms) runs the same passes as record(): two scopes, the
// G-buffer's and "pipeline", both timed, and every image the same bits.
TEST_P(Timing, OneScopeRecordsTheSamePassesUnderTwoScopes) {
    RunConfig c = configAt(160, 90);
    c.kernel = "alchemy_fast";
    auto chain = PassChain::create(gpu(), c);
    ASSERT_TRUE(chain) << chain.error().message;
    std::map<std::string, HostImage> images[2];
    // One scope first, on a chain that has rendered nothing: a pass it left
    // out would leave its images unwritten.
    for (int one : {1, 0}) {
        gpu().beginFrame();
        if (one) (*chain)->recordInOneScope();
        else (*chain)->record();
        ASSERT_TRUE(gpu().endFrame());
        const auto scopes = gpu().scopeTimes();
        if (one) {
            ASSERT_EQ(scopes.size(), 2u);
            EXPECT_EQ(scopes[0].name, "gbuffer");
            EXPECT_EQ(scopes[1].name, "pipeline");
        } else {
            EXPECT_EQ(scopes.size(), (*chain)->passCount());
        }
        for (const auto& s : scopes) EXPECT_GT(s.gpuMs, 0) << s.name;
        for (const auto& out : userOutputs(c)) {
            auto img = (*chain)->read(out.image);
            ASSERT_TRUE(img) << img.error().message;
            images[one][out.image] = std::move(*img);
        }
    }
    ASSERT_FALSE(images[0].empty());
    for (const auto& [name, img] : images[0]) EXPECT_TRUE(img.pixels == images[1][name].pixels) << name;
}

// A clock given by the caller (the benchmark's later repetitions) is kept,
// whatever this measurement's own probe would have chosen.
TEST_P(Timing, AGivenClockIsKept) {
    const RunConfig c = configAt(160, 90);
    auto chain = PassChain::create(gpu(), c);
    ASSERT_TRUE(chain) << chain.error().message;
    TimingOptions o = defaultTimingOptions(gpu().info());
    o.warmup = 0;
    o.steadyWarmup = false;
    o.frames = 3;
    o.maxNoise = 0;
    o.clock = "wall";
    auto t = measurePasses(gpu(), **chain, o);
    ASSERT_TRUE(t) << t.error().message;
    EXPECT_EQ(t->clock, "wall");
    EXPECT_EQ(t->mode, TimingMode::Drained);
    EXPECT_EQ(t->frame.ms.size(), 3u);
}

// A planted slowdown (kernels/assemble.cpp) adds work whose result is never
// written: every image stays bit-identical, so a timing A/B compares the same output.
TEST_P(Timing, APlantedSlowdownLeavesEveryImageUnchanged) {
    const RunConfig c = configAt(96, 54);
    auto plain = PassChain::create(gpu(), c);
    auto planted = PassChain::create(gpu(), c, {}, {{"ao", 300}, {"blur", 50}, {"composite", 10}});
    ASSERT_TRUE(plain && planted);
    for (auto* chain : {plain->get(), planted->get()}) {
        gpu().beginFrame();
        chain->record();
        ASSERT_TRUE(gpu().endFrame());
    }
    for (const auto& out : userOutputs(c)) {
        auto a = (*plain)->read(out.image), b = (*planted)->read(out.image);
        ASSERT_TRUE(a && b);
        EXPECT_TRUE(a->pixels == b->pixels) << out.image;
    }
}

CAVITY_ALL_BACKENDS(Timing);

// The median's interval narrows as 1/sqrt(n): a sample four times longer
// from the same distribution has about half the noise.
TEST(MedianNoise, ShrinksWithTheSquareRootOfTheSampleCount) {
    auto sample = [](int n) {
        std::vector<double> v;
        unsigned s = 12345;
        for (int i = 0; i < n; ++i) {
            s = s * 1103515245u + 12345u;
            v.push_back(1.0 + 0.05 * double((s >> 8) % 1000) / 1000.0);
        }
        return v;
    };
    EXPECT_TRUE(std::isinf(medianNoise({1, 2, 3})));
    const double n400 = medianNoise(sample(400)), n1600 = medianNoise(sample(1600));
    EXPECT_GT(n400, 0);
    EXPECT_NEAR(n1600 / n400, 0.5, 0.15);
    EXPECT_EQ(medianNoise(std::vector<double>(50, 2.0)), 0.0);
}

}  // namespace
}  // namespace cavity::test
