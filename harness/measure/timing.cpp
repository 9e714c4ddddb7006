#include "measure/timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace cavity::measure {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
double secondsSince(Clock::time_point t0) { return msSince(t0) / 1000.0; }

void finalize(Series& s) { s.stats = summarize(s.ms); }

// The frames of one submission (batch mode) or of one run of drained frames.
struct Group {
    std::vector<std::vector<double>> passMs;   // [frame][pass]
    std::vector<double> frameMs;               // per frame, on the clock in use
    std::vector<double> frameWall;             // per frame (batch: the batch's wall time shared out)
    std::vector<double> frameGpu;              // per frame, sum of its pass timestamps
    std::vector<bool> accepted;                // per frame: passed the clock check
    std::string rejection;                     // why the first rejected frame was rejected
};

class Runner {
public:
    Runner(gpu::Backend& gpu, std::span<PassChain* const> chains, const ClockCheck& check)
        : gpu_(gpu), chains_(chains), n_(chains[0]->passCount()), check_(check) {}

    // `count` frames starting at frame number `first` (which picks the chain).
    Result<Group> run(TimingMode mode, bool wallClock, long first, int count) {
        if (wallClock) return runWall(first, count);
        return mode == TimingMode::Batch ? runBatch(first, count) : runDrained(first, count);
    }

private:
    PassChain& chain(long f) { return *chains_[size_t(f) % chains_.size()]; }

    Status takeFrame(Group& g, const std::vector<gpu::ScopeTime>& scopes, size_t frame) {
        std::vector<double> ms(n_);
        double sum = 0;
        for (size_t i = 0; i < n_; ++i) {
            ms[i] = scopes[frame * n_ + i].gpuMs;
            sum += ms[i];
        }
        g.passMs.push_back(std::move(ms));
        g.frameGpu.push_back(sum);
        g.frameMs.push_back(sum);
        return {};
    }

    Status expectScopes(const std::vector<gpu::ScopeTime>& scopes, int frames) {
        if (scopes.size() == size_t(frames) * n_) return {};
        return internal("backend returned " + std::to_string(scopes.size()) + " timestamp scopes for " +
                        std::to_string(frames) + " frames of " + std::to_string(n_) + " passes");
    }

    // Back to back in one submission; a barrier between frames orders one
    // frame's reads before the next frame's writes of the same images.
    Result<Group> runBatch(long first, int count) {
        Group g;
        const auto t0 = Clock::now();
        gpu_.beginFrame();
        for (int k = 0; k < count; ++k) {
            if (k) gpu_.barrier();
            chain(first + k).record();
        }
        CAVITY_TRY(gpu_.endFrame());
        const double wall = msSince(t0);
        const auto scopes = gpu_.scopeTimes();
        CAVITY_TRY(expectScopes(scopes, count));
        double gpuSum = 0;
        for (int k = 0; k < count; ++k) {
            CAVITY_TRY(takeFrame(g, scopes, size_t(k)));
            gpuSum += g.frameGpu.back();
            g.frameWall.push_back(wall / count);
        }
        const bool ok = check_.trusted(gpuSum, wall);
        g.accepted.assign(size_t(count), ok);
        if (!ok) g.rejection = describe("batch of " + std::to_string(count) + " frames", gpuSum, wall);
        return g;
    }

    // One frame per submission, the queue drained before and after.
    Result<Group> runDrained(long first, int count) {
        Group g;
        for (int k = 0; k < count; ++k) {
            CAVITY_TRY(gpu_.finish());
            const auto t0 = Clock::now();
            gpu_.beginFrame();
            chain(first + k).record();
            CAVITY_TRY(gpu_.endFrame());
            const double wall = msSince(t0);
            const auto scopes = gpu_.scopeTimes();
            CAVITY_TRY(expectScopes(scopes, 1));
            CAVITY_TRY(takeFrame(g, scopes, 0));
            g.frameWall.push_back(wall);
            const bool ok = check_.trusted(g.frameGpu.back(), wall);
            g.accepted.push_back(ok);
            if (!ok && g.rejection.empty()) g.rejection = describe("frame", g.frameGpu.back(), wall);
        }
        return g;
    }

    // The timestamps do not bracket the work: each pass alone, drained.
    Result<Group> runWall(long first, int count) {
        Group g;
        for (int k = 0; k < count; ++k) {
            std::vector<double> ms(n_);
            double sum = 0;
            for (size_t i = 0; i < n_; ++i) {
                CAVITY_TRY(gpu_.finish());
                const auto t0 = Clock::now();
                gpu_.beginFrame();
                chain(first + k).recordPass(i);
                CAVITY_TRY(gpu_.endFrame());
                ms[i] = msSince(t0);
                sum += ms[i];
            }
            double gpuSum = 0;
            for (const auto& s : gpu_.scopeTimes()) gpuSum += s.gpuMs;
            g.passMs.push_back(std::move(ms));
            g.frameMs.push_back(sum);
            g.frameWall.push_back(sum);
            g.frameGpu.push_back(gpuSum);
            g.accepted.push_back(true);
        }
        return g;
    }

    static std::string describe(const std::string& what, double gpuMs, double wallMs) {
        char b[160];
        std::snprintf(b, sizeof b, "%s: timestamps %.3f ms against %.3f ms wall", what.c_str(), gpuMs, wallMs);
        return b;
    }

    gpu::Backend& gpu_;
    std::span<PassChain* const> chains_;
    size_t n_;
    const ClockCheck& check_;
};

// Decides whether the timestamps bracket the work: a few drained frames, the
// frame against its wall time, and each pass timed alone against its own (a
// frame total can hide a pass whose work lands in the next scope: llvmpipe GL
// defers draws to the next flush, so a raster pass reads 0.1 ms and the pass
// after it pays). Returns the note explaining a "no", empty for a "yes".
Result<std::string> clockVerdict(gpu::Backend& gpu, PassChain& chain, const ClockCheck& check, double& frameMs) {
    const size_t n = chain.passCount();
    std::vector<std::vector<double>> stamps(n), alone(n);
    std::vector<double> frameGpu, frameWall;
    bool anyZero = false;
    for (int f = 0; f < 3; ++f) {
        CAVITY_TRY(gpu.finish());
        const auto t0 = Clock::now();
        gpu.beginFrame();
        chain.record();
        CAVITY_TRY(gpu.endFrame());
        frameWall.push_back(msSince(t0));
        const auto scopes = gpu.scopeTimes();
        if (scopes.size() != n) return internal("backend returned " + std::to_string(scopes.size()) +
                                                " timestamp scopes for " + std::to_string(n) + " passes");
        double sum = 0;
        for (size_t i = 0; i < n; ++i) {
            stamps[i].push_back(scopes[i].gpuMs);
            anyZero |= !(scopes[i].gpuMs > 0);
            sum += scopes[i].gpuMs;
        }
        frameGpu.push_back(sum);
    }
    for (int f = 0; f < 3; ++f)
        for (size_t i = 0; i < n; ++i) {
            CAVITY_TRY(gpu.finish());
            const auto t0 = Clock::now();
            gpu.beginFrame();
            chain.recordPass(i);
            CAVITY_TRY(gpu.endFrame());
            alone[i].push_back(msSince(t0));
        }
    const double gpuMedian = summarize(frameGpu).median, wallMedian = summarize(frameWall).median;
    std::string badPass;
    for (size_t i = 0; i < n && badPass.empty(); ++i) {
        const double s = summarize(stamps[i]).median, w = summarize(alone[i]).median;
        if (!check.trusted(s, w)) {
            char b[160];
            std::snprintf(b, sizeof b, "; pass %s: timestamps %.3f ms, drained wall %.3f ms",
                          chain.passes()[i].name.c_str(), s, w);
            badPass = b;
        }
    }
    const bool trusted = !anyZero && badPass.empty() && check.trusted(gpuMedian, wallMedian);
    frameMs = trusted ? gpuMedian : wallMedian;
    if (trusted) return std::string();
    char note[512];
    std::snprintf(note, sizeof note,
                  "GPU timestamps do not bracket the work (median frame: timestamps %.3f ms, drained wall %.3f ms%s%s); "
                  "per-pass times are drained wall-clock times",
                  gpuMedian, wallMedian, anyZero ? ", a pass read 0" : "", badPass.c_str());
    return std::string(note);
}

double groupMedian(const Group& g) { return summarize(g.frameMs).median; }

}  // namespace

const char* timingModeName(TimingMode m) { return m == TimingMode::Batch ? "batch" : "drained"; }

TimingOptions defaultTimingOptions(const gpu::DeviceInfo& device) {
    TimingOptions o;
    if (device.softwareRenderer) {
        o.steadyWarmup = false;
        o.maxNoise = 0;
    }
    return o;
}

bool ClockCheck::trusted(double gpuMs, double wallMs) const {
    if (!(gpuMs > 0)) return false;
    if (gpuMs > wallMs * maxOverWall + slopMs) return false;
    return gpuMs >= minFraction * wallMs || wallMs - gpuMs <= overheadMs;
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

Result<Timing> measurePasses(gpu::Backend& gpu, std::span<PassChain* const> chains, const TimingOptions& o,
                       GpuClocks* clocks, const ClockCheck& check) {
    if (chains.empty()) return internal("measure: no pass chain");
    if (o.frames < 1) return internal("measure: frames must be at least 1");
    PassChain& first = *chains[0];
    const size_t n = first.passCount();
    Timing t;
    t.mode = o.mode;

    // 1. The clock, and a frame time to size the batches with.
    double frameMs = 0;
    CAVITY_ASSIGN(const std::string note, clockVerdict(gpu, first, check, frameMs));
    t.clock = note.empty() ? "gpu-timestamp" : "wall";
    t.clockNote = note;
    if (o.clock && *o.clock != t.clock) {
        // Repetitions of one configuration stay on the clock of the first;
        // its batches are still checked one by one below.
        t.clock = *o.clock;
        t.clockNote = "kept the " + t.clock + " clock of this configuration's first measurement" +
                      (note.empty() ? std::string() : " (this one's probe: " + note + ")");
    }
    const bool wall = t.clock == "wall";
    if (wall) t.mode = TimingMode::Drained;   // the wall clock can only time a pass alone
    t.batchFrames = std::clamp(int(std::ceil(o.batchMs / std::max(frameMs, 1e-3))), 1, std::max(1, o.maxBatch));
    if (wall) t.batchFrames = 1;

    Runner runner(gpu, chains, check);
    std::vector<GpuClockSample> clockSamples;
    auto sampleClock = [&] {
        if (!clocks) return std::optional<GpuClockSample>();
        auto s = clocks->sample();
        if (s) clockSamples.push_back(*s);
        return s;
    };
    long frameNo = 0;

    // 2. Warm-up: at least o.warmup frames, then (steadyWarmup) on until two
    // consecutive batches agree on the median frame time within
    // steadyTolerance and the SM clock read the same after both.
    {
        const auto t0 = Clock::now();
        double previous = -1;
        std::optional<GpuClockSample> lastClock = sampleClock();
        double lastWarmGpuMs = 0;
        while (true) {
            const bool enough = t.warmupFrames >= o.warmup;
            if (enough && (!o.steadyWarmup || t.steady || secondsSince(t0) >= o.warmupSeconds)) break;
            const int count = o.steadyWarmup ? t.batchFrames : std::min(t.batchFrames, o.warmup - t.warmupFrames);
            CAVITY_ASSIGN(Group g, runner.run(t.mode, wall, frameNo, count));
            frameNo += long(g.frameMs.size());
            t.warmupFrames += int(g.frameMs.size());
            const double m = groupMedian(g);
            lastWarmGpuMs = summarize(g.frameGpu).median;
            const auto clock = sampleClock();
            const bool clockSteady = !clock || !lastClock || clock->smMhz == lastClock->smMhz;
            if (previous > 0 && std::fabs(m - previous) <= o.steadyTolerance * previous && clockSteady) t.steady = true;
            previous = m;
            lastClock = clock;
        }
        t.warmupSeconds = secondsSince(t0);
        t.steadyChecked = o.steadyWarmup;
        // The probe's drained frames carry first-use costs (NVIDIA's GL
        // compiles a fragment pipeline at its first draws: 8 ms probe frames,
        // 0.1 ms warm ones), so size the batches again from the warm GPU
        // time: a batch of 3 such frames was 0.3 ms of GPU work in 0.7 ms of
        // wall time and failed the clock check on submission overhead alone.
        if (!wall && t.mode == TimingMode::Batch && lastWarmGpuMs > 0)
            t.batchFrames = std::clamp(int(std::ceil(o.batchMs / std::max(lastWarmGpuMs, 1e-3))), 1,
                                       std::max(1, o.maxBatch));
    }
    clockSamples.clear();

    // 3. Measurement.
    t.passes.assign(n, {});
    for (size_t i = 0; i < n; ++i) t.passes[i].name = first.passes()[i].name;
    t.frame.name = t.frameWall.name = t.frameGpu.name = "frame";
    const auto t0 = Clock::now();
    sampleClock();
    int accepted = 0, groups = 0, rejectedGroups = 0;
    while (true) {
        const double elapsed = secondsSince(t0);
        if (accepted >= o.frames) {
            if (o.maxNoise <= 0) {
                t.stop = "frames";
                break;
            }
            double noise = medianNoise(t.frame.ms);
            for (const auto& p : t.passes) noise = std::max(noise, medianNoise(p.ms));
            t.noise = noise;
            if (noise <= o.maxNoise) {
                t.stop = "noise";
                break;
            }
            if (elapsed >= o.maxSeconds) {
                t.stop = "time";
                break;
            }
        }
        // A clock that keeps failing its check is the wrong clock: say so
        // rather than measure forever.
        if (groups >= 8 && 2 * rejectedGroups > groups)
            return internal("the clock check rejected " + std::to_string(rejectedGroups) + " of " +
                            std::to_string(groups) + " batches on the " + t.clock + " clock (" + t.rejectedNote + ")");
        // A batch is always whole, so that its wall time is mostly GPU work
        // (the clock check compares the two); with a fixed count only the
        // frames still wanted are kept. Drained frames stop at the count.
        int count = t.batchFrames;
        if (o.maxNoise <= 0 && t.mode != TimingMode::Batch) count = std::min(count, o.frames - accepted);
        CAVITY_ASSIGN(Group g, runner.run(t.mode, wall, frameNo, count));
        sampleClock();
        frameNo += long(g.frameMs.size());
        ++groups;
        rejectedGroups += std::count(g.accepted.begin(), g.accepted.end(), false) > 0;
        for (size_t f = 0; f < g.frameMs.size(); ++f) {
            if (o.maxNoise <= 0 && accepted >= o.frames) break;
            if (!g.accepted[f]) {
                ++t.rejectedFrames;
                continue;
            }
            ++accepted;
            for (size_t i = 0; i < n; ++i) t.passes[i].ms.push_back(g.passMs[f][i]);
            t.frame.ms.push_back(g.frameMs[f]);
            t.frameWall.ms.push_back(g.frameWall[f]);
            t.frameGpu.ms.push_back(g.frameGpu[f]);
        }
        if (t.rejectedNote.empty()) t.rejectedNote = g.rejection;
    }
    t.seconds = secondsSince(t0);
    if (o.maxNoise <= 0) {
        double noise = medianNoise(t.frame.ms);
        for (const auto& p : t.passes) noise = std::max(noise, medianNoise(p.ms));
        t.noise = noise;
    }
    for (auto& s : t.passes) finalize(s);
    finalize(t.frame);
    finalize(t.frameWall);
    finalize(t.frameGpu);
    if (clocks) t.clocks = summarizeClocks(clockSamples, clocks->source(), clocks->device());
    return t;
}

}  // namespace cavity::measure