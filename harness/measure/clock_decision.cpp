#include "measure/frames.h"

#include <cstdio>

namespace cavity::measure {

// Decides whether the timestamps bracket the work: a few drained frames, the
// frame against its wall time, and each pass timed alone against its own (a
// frame total can hide a pass whose work lands in the next scope: llvmpipe GL
// defers draws to the next flush, so a raster pass reads almost nothing and
// the pass after it pays). Returns the note explaining a "no", empty for a "yes".
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

bool ClockCheck::trusted(double gpuMs, double wallMs) const {
    if (distrustFirst > 0) {
        --distrustFirst;
        return false;
    }
    if (trustRest) return true;
    if (!(gpuMs > 0)) return false;
    if (gpuMs > wallMs * maxOverWall + slopMs) return false;
    return gpuMs >= minFraction * wallMs || wallMs - gpuMs <= overheadMs;
}

}  // namespace cavity::measure
