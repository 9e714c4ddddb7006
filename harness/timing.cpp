#include "timing.h"

#include <chrono>

namespace cavity {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

void finalize(Series& s) { s.stats = summarize(s.ms); }

}  // namespace

bool ClockCheck::trusted(double gpuMs, double wallMs) const {
    if (!(gpuMs > 0)) return false;
    if (gpuMs > wallMs * maxOverWall + slopMs) return false;
    return gpuMs >= minFraction * wallMs || wallMs - gpuMs <= overheadMs;
}

Result<Timing> measure(gpu::Backend& gpu, PassChain& chain, int warmup, int frames, const ClockCheck& check) {
    Timing t;
    const size_t n = chain.passCount();
    std::vector<Series> gpuPasses(n);
    for (size_t i = 0; i < n; ++i) gpuPasses[i].name = chain.passes()[i].name;
    t.frameWall.name = "frame";
    t.frameGpu.name = "frame";

    for (int f = 0; f < warmup + frames; ++f) {
        CAVITY_TRY(gpu.finish());
        const auto t0 = Clock::now();
        gpu.beginFrame();
        chain.record();
        CAVITY_TRY(gpu.endFrame());
        const double wall = msSince(t0);
        if (f < warmup) continue;
        const auto scopes = gpu.scopeTimes();
        if (scopes.size() != n) return internal("backend returned " + std::to_string(scopes.size()) +
                                                " timestamp scopes for " + std::to_string(n) + " passes");
        double sum = 0;
        for (size_t i = 0; i < n; ++i) {
            gpuPasses[i].ms.push_back(scopes[i].gpuMs);
            sum += scopes[i].gpuMs;
        }
        t.frameWall.ms.push_back(wall);
        t.frameGpu.ms.push_back(sum);
    }
    finalize(t.frameWall);
    finalize(t.frameGpu);

    bool anyZero = false;
    for (auto& s : gpuPasses) {
        finalize(s);
        anyZero |= !(s.stats.min > 0);
    }
    // A frame total can hide a pass whose work lands in the next scope
    // (llvmpipe GL defers draws to the next flush, so a raster pass reads
    // 0.1 ms and the pass after it pays): time each pass alone, drained, a
    // few times and check every pass against its own wall time.
    std::vector<Series> calib(n);
    for (int f = 0; f < 3; ++f)
        for (size_t i = 0; i < n; ++i) {
            CAVITY_TRY(gpu.finish());
            const auto t0 = Clock::now();
            gpu.beginFrame();
            chain.recordPass(i);
            CAVITY_TRY(gpu.endFrame());
            calib[i].ms.push_back(msSince(t0));
        }
    std::string badPass;
    for (size_t i = 0; i < n; ++i) {
        finalize(calib[i]);
        if (!check.trusted(gpuPasses[i].stats.median, calib[i].stats.median) && badPass.empty()) {
            char b[160];
            std::snprintf(b, sizeof b, "pass %s: timestamps %.3f ms, drained wall %.3f ms", gpuPasses[i].name.c_str(),
                          gpuPasses[i].stats.median, calib[i].stats.median);
            badPass = b;
        }
    }
    if (!anyZero && badPass.empty() && check.trusted(t.frameGpu.stats.median, t.frameWall.stats.median)) {
        t.clock = "gpu-timestamp";
        t.passes = std::move(gpuPasses);
        t.frame = t.frameGpu;
        return t;
    }

    // The timestamps do not bracket the work: time each pass alone, drained.
    char note[512];
    std::snprintf(note, sizeof note,
                  "GPU timestamps do not bracket the work (median frame: timestamps %.3f ms, drained wall %.3f ms%s%s); "
                  "per-pass times are drained wall-clock times",
                  t.frameGpu.stats.median, t.frameWall.stats.median, anyZero ? ", a pass read 0" : "",
                  badPass.empty() ? "" : ("; " + badPass).c_str());
    t.clock = "wall";
    t.clockNote = note;
    t.passes.assign(n, {});
    for (size_t i = 0; i < n; ++i) t.passes[i].name = chain.passes()[i].name;
    for (int f = 0; f < frames; ++f) {
        for (size_t i = 0; i < n; ++i) {
            CAVITY_TRY(gpu.finish());
            const auto t0 = Clock::now();
            gpu.beginFrame();
            chain.recordPass(i);
            CAVITY_TRY(gpu.endFrame());
            t.passes[i].ms.push_back(msSince(t0));
        }
    }
    for (auto& s : t.passes) finalize(s);
    t.frame = t.frameWall;
    return t;
}

}  // namespace cavity
