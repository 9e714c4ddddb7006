// How frames are run and timed for one measurement (measure/timing.h):
// batches of back-to-back frames, drained frames, or passes timed alone on
// the wall clock, each frame checked against the clock it is timed by. And
// the clock decision that picks between GPU timestamps and the wall clock.
// Internal to measure/.
#pragma once

#include "measure/namespace.h"
#include "measure/timing.h"

#include <chrono>
#include <span>
#include <string>
#include <vector>

namespace cavity::measure {

using Clock = std::chrono::steady_clock;
inline double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
inline double secondsSince(Clock::time_point t0) { return msSince(t0) / 1000.0; }

inline void finalize(Series& s) { s.stats = summarize(s.ms); }

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

inline double groupMedian(const Group& g) { return summarize(g.frameMs).median; }

// Decides whether the timestamps bracket the work; returns the note
// explaining a "no", empty for a "yes", and the frame time in frameMs.
Result<std::string> clockVerdict(gpu::Backend& gpu, PassChain& chain, const ClockCheck& check, double& frameMs);

}  // namespace cavity::measure
