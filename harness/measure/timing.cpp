#include "measure/timing.h"

#include "measure/frames.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

namespace cavity::measure {

const char* timingModeName(TimingMode m) { return m == TimingMode::Batch ? "batch" : "drained"; }

TimingOptions defaultTimingOptions(const gpu::DeviceInfo& device) {
    TimingOptions o;
    if (device.softwareRenderer) {
        o.steadyWarmup = false;
        o.maxNoise = 0;
    }
    return o;
}

double medianNoise(std::vector<double> x) {
    const size_t n = x.size();
    if (n < 8) return std::numeric_limits<double>::infinity();
    std::sort(x.begin(), x.end());
    // Ranks of the distribution-free interval: the number of samples below
    // the median is Binomial(n, 1/2), within n/2 -+ 1.96 sqrt(n)/2 at 95%.
    const double half = 0.98 * std::sqrt(double(n));
    const auto lo = size_t(std::max(0.0, std::floor(double(n) / 2 - half)));
    const auto hi = size_t(std::min(double(n - 1), std::ceil(double(n) / 2 + half) - 1));
    const double median = summarize(x).median;
    if (!(median > 0)) return std::numeric_limits<double>::infinity();
    return (x[hi] - x[lo]) / (2 * median);
}

Result<Timing> measurePasses(gpu::Backend& gpu, PassChain& chain, const TimingOptions& options, GpuClocks* clocks,
                       const ClockCheck& check) {
    PassChain* one[] = {&chain};
    return measurePasses(gpu, std::span<PassChain* const>(one), options, clocks, check);
}

namespace {

// Frames a batch holds so that it takes about o.batchMs of GPU time.
int batchFramesFor(const TimingOptions& o, double frameMs) {
    return std::clamp(int(std::ceil(o.batchMs / std::max(frameMs, 1e-3))), 1, std::max(1, o.maxBatch));
}

// The largest median noise over the frame and every pass.
double worstNoise(const Timing& t) {
    double noise = medianNoise(t.frame.ms);
    for (const auto& p : t.passes) noise = std::max(noise, medianNoise(p.ms));
    return noise;
}

// 1. A cold probe: a frame time to size the warm-up's batches with, and the
// clock the warm-up runs on. It decides nothing: a cold GPU (first-use
// compiles, a low clock, a first configuration of its API in a process) can
// fail the check a warm one passes (study 2026-12-01_h200_verdict: some
// configurations took "wall" from a cold probe).
Status probeClock(gpu::Backend& gpu, PassChain& chain, const TimingOptions& o, const ClockCheck& check, Timing& t) {
    double frameMs = 0;
    CAVITY_ASSIGN(const std::string note, clockVerdict(gpu, chain, check, frameMs));
    t.clock = o.clock ? *o.clock : note.empty() ? "gpu-timestamp" : "wall";
    t.clockNote = note;
    if (t.clock == "wall") t.mode = TimingMode::Drained;   // the wall clock can only time a pass alone
    t.batchFrames = t.clock == "wall" ? 1 : batchFramesFor(o, frameMs);
    return {};
}

// 2b. The decision, on the warm GPU after warm-up. Every repetition decides
// again; one that disagrees with the configuration's first (o.clock) says so.
// Returns whether the clock changed from the one the warm-up ran on.
Result<bool> decideWarm(gpu::Backend& gpu, PassChain& chain, const TimingOptions& o, const ClockCheck& check, Timing& t) {
    double frameMs = 0;
    const std::string before = t.clock, cold = t.clockNote;
    // A software renderer's probes pass or fail by the host's load: there a
    // cold failure keeps the wall clock, and repetitions keep their first's
    // clock so that they pool.
    if (check.coldCounts.value_or(gpu.info().softwareRenderer) && (o.clock || !cold.empty())) {
        t.clock = o.clock ? *o.clock : "wall";
        t.clockNote = o.clock ? "kept the " + t.clock + " clock of this configuration's first measurement (software renderer)"
                              : cold + " (a cold probe's failure is enough on a software renderer)";
        if (t.clock == "gpu-timestamp" && o.clock) t.clockNote.clear();
        t.mode = t.clock == "wall" ? TimingMode::Drained : o.mode;
        if (t.clock == "wall") t.batchFrames = 1;
        return t.clock != before;
    }
    CAVITY_ASSIGN(std::string note, clockVerdict(gpu, chain, check, frameMs));
    // A failed check is tried twice more before the clock moves: timestamps
    // that miss the work fail every time, while a hiccup of the host during
    // the drained wall-clock frames fails one (on the H200, with one check
    // each, some repetitions moved to the wall clock, and their
    // configurations had no verdict: mixed clocks; study
    // 2026-12-03_h200_sensitivity2).
    std::string passedOnRetry;
    for (int retry = 0; retry < kClockRetries && !note.empty(); ++retry) {
        CAVITY_ASSIGN(const std::string again, clockVerdict(gpu, chain, check, frameMs));
        if (again.empty()) passedOnRetry = std::exchange(note, std::string());
    }
    t.clock = note.empty() ? "gpu-timestamp" : "wall";
    std::string why = t.clock == "gpu-timestamp" ? "timestamps agree with the drained wall clock on the warm GPU"
                                                 : note + " (on the warm GPU, in " + std::to_string(kClockRetries + 1) +
                                                       " checks)";
    if (!passedOnRetry.empty()) why += "; a check that failed passed when tried again: " + passedOnRetry;
    if (o.clock && *o.clock != t.clock)
        why += "; re-decided: this configuration's first measurement used the " + *o.clock + " clock";
    else if (!cold.empty() && t.clock == "gpu-timestamp")
        why += "; the cold probe before warm-up had said: " + cold;
    t.clockNote = t.clock == "gpu-timestamp" && why.find("re-decided") == std::string::npos && cold.empty() &&
                          passedOnRetry.empty()
                      ? ""
                      : why;
    t.mode = t.clock == "wall" ? TimingMode::Drained : o.mode;
    if (t.clock != before) t.batchFrames = t.clock == "wall" ? 1 : batchFramesFor(o, frameMs);
    return t.clock != before;
}

// One measurement in progress: the runner, the clock samples and the frame
// count shared by warm-up and measurement.
class Measurement {
public:
    Measurement(gpu::Backend& gpu, std::span<PassChain* const> chains, const TimingOptions& o, GpuClocks* clocks,
                const ClockCheck& check, Timing& t)
        : runner_(gpu, chains, check), o_(o), clocks_(clocks), t_(t), wall_(t.clock == "wall") {}

    // 2. Warm-up: at least o.warmup frames, then (steadyWarmup) on until two
    // consecutive batches agree on the median frame time within
    // steadyTolerance and the SM clock read the same after both.
    Status warmUp() {
        const auto t0 = Clock::now();
        double previous = -1, lastWarmGpuMs = 0;
        std::optional<GpuClockSample> lastClock = sampleClock();
        while (true) {
            const bool enough = t_.warmupFrames >= o_.warmup;
            if (enough && (!o_.steadyWarmup || t_.steady || secondsSince(t0) >= o_.warmupSeconds)) break;
            const int count = o_.steadyWarmup ? t_.batchFrames : std::min(t_.batchFrames, o_.warmup - t_.warmupFrames);
            CAVITY_ASSIGN(Group g, run(count));
            t_.warmupFrames += int(g.frameMs.size());
            const double m = groupMedian(g);
            lastWarmGpuMs = summarize(g.frameGpu).median;
            const auto clock = sampleClock();
            const bool clockSteady = !clock || !lastClock || clock->smMhz == lastClock->smMhz;
            if (previous > 0 && std::fabs(m - previous) <= o_.steadyTolerance * previous && clockSteady) t_.steady = true;
            previous = m;
            lastClock = clock;
        }
        t_.warmupSeconds = secondsSince(t0);
        t_.steadyChecked = o_.steadyWarmup;
        // The probe's drained frames carry first-use costs (NVIDIA's GL
        // compiles a fragment pipeline at its first draws, which makes its
        // probe frames far longer than its warm ones), so size the batches
        // again from the warm GPU time: a batch sized from the probe was too
        // short, its wall time mostly submission overhead, and failed the
        // clock check on that alone.
        if (!wall_ && t_.mode == TimingMode::Batch && lastWarmGpuMs > 0) t_.batchFrames = batchFramesFor(o_, lastWarmGpuMs);
        clockSamples_.clear();
        return {};
    }

    // 3. Measurement, batch after batch until the stop rule says enough.
    Status measure(const PassChain& first) {
        t_.passes.assign(first.passCount(), {});
        for (size_t i = 0; i < first.passCount(); ++i) t_.passes[i].name = first.passes()[i].name;
        t_.frame.name = t_.frameWall.name = t_.frameGpu.name = "frame";
        t_.pipeline.name = "pipeline";
        const auto t0 = Clock::now();
        sampleClock();
        while (!stopRule(secondsSince(t0))) {
            // A clock that keeps failing its check is the wrong clock: say so
            // rather than measure forever.
            if (groups_ >= 8 && 2 * rejectedGroups_ > groups_)
                return internal("the clock check rejected " + std::to_string(rejectedGroups_) + " of " +
                                std::to_string(groups_) + " batches on the " + t_.clock + " clock (" + t_.rejectedNote + ")");
            // A batch is always whole, so that its wall time is mostly GPU work
            // (the clock check compares the two); with a fixed count only the
            // frames still wanted are kept. Drained frames stop at the count.
            int count = t_.batchFrames;
            if (o_.maxNoise <= 0 && t_.mode != TimingMode::Batch) count = std::min(count, o_.frames - accepted_);
            CAVITY_ASSIGN(Group g, run(count));
            sampleClock();
            keep(g);
        }
        t_.seconds = secondsSince(t0);
        if (o_.maxNoise <= 0) t_.noise = worstNoise(t_);
        return {};
    }

    const std::vector<GpuClockSample>& clockSamples() const { return clockSamples_; }

    // The warm decision moved the clock: measure on it, after one batch on it
    // to warm its mode (discarded).
    Status clockChanged() {
        wall_ = t_.clock == "wall";
        CAVITY_ASSIGN(const Group g, run(t_.batchFrames));
        (void)g;
        return {};
    }

private:
    Result<Group> run(int count) {
        CAVITY_ASSIGN(Group g, runner_.run(t_.mode, wall_, frameNo_, count));
        frameNo_ += long(g.frameMs.size());
        return g;
    }

    std::optional<GpuClockSample> sampleClock() {
        if (!clocks_) return std::nullopt;
        auto s = clocks_->sample();
        if (s) clockSamples_.push_back(*s);
        return s;
    }

    // The stop rule: with a fixed count, once it is reached; with a noise
    // target, once the worst median noise is under it or the time is up.
    bool stopRule(double elapsed) {
        if (o_.hardTimeLimit && elapsed >= o_.maxSeconds && accepted_ >= kMinTimedFrames) {
            t_.noise = worstNoise(t_);
            t_.stop = "time";
            return true;
        }
        if (accepted_ < o_.frames) return false;
        if (o_.maxNoise <= 0) {
            t_.stop = "frames";
            return true;
        }
        t_.noise = worstNoise(t_);
        if (t_.noise <= o_.maxNoise) t_.stop = "noise";
        else if (elapsed >= o_.maxSeconds) t_.stop = "time";
        return !t_.stop.empty();
    }

    // The batch's accepted frames, up to the count when it is fixed.
    void keep(const Group& g) {
        ++groups_;
        rejectedGroups_ += std::count(g.accepted.begin(), g.accepted.end(), false) > 0;
        for (size_t f = 0; f < g.frameMs.size(); ++f) {
            if (o_.maxNoise <= 0 && accepted_ >= o_.frames) break;
            if (!g.accepted[f]) {
                ++t_.rejectedFrames;
                continue;
            }
            ++accepted_;
            double pipeline = 0;
            for (size_t i = 0; i < t_.passes.size(); ++i) {
                t_.passes[i].ms.push_back(g.passMs[f][i]);
                if (t_.passes[i].name != "gbuffer") pipeline += g.passMs[f][i];
            }
            t_.pipeline.ms.push_back(pipeline);
            t_.frame.ms.push_back(g.frameMs[f]);
            t_.frameWall.ms.push_back(g.frameWall[f]);
            t_.frameGpu.ms.push_back(g.frameGpu[f]);
        }
        if (t_.rejectedNote.empty()) t_.rejectedNote = g.rejection;
    }

    Runner runner_;
    const TimingOptions& o_;
    GpuClocks* clocks_;
    Timing& t_;
    bool wall_;
    std::vector<GpuClockSample> clockSamples_;
    long frameNo_ = 0;
    int accepted_ = 0, groups_ = 0, rejectedGroups_ = 0;
};

}  // namespace

Result<Timing> measurePasses(gpu::Backend& gpu, std::span<PassChain* const> chains, const TimingOptions& o,
                             GpuClocks* clocks, const ClockCheck& check) {
    if (chains.empty()) return internal("measure: no pass chain");
    if (o.frames < 1) return internal("measure: frames must be at least 1");
    Timing t;
    t.mode = o.mode;
    CAVITY_TRY(probeClock(gpu, *chains[0], o, check, t));
    Measurement m(gpu, chains, o, clocks, check, t);
    CAVITY_TRY(m.warmUp());
    CAVITY_ASSIGN(const bool changed, decideWarm(gpu, *chains[0], o, check, t));
    if (changed) CAVITY_TRY(m.clockChanged());
    CAVITY_TRY(m.measure(*chains[0]));
    for (auto& s : t.passes) finalize(s);
    finalize(t.frame);
    finalize(t.pipeline);
    finalize(t.frameWall);
    finalize(t.frameGpu);
    if (clocks) t.clocks = summarizeClocks(m.clockSamples(), clocks->source(), clocks->device());
    return t;
}

}  // namespace cavity::measure
