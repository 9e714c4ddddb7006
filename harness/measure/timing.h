// Measuring a pipeline on a GPU that manages its own clock.
//
// A GPU left idle between frames lowers its clock (docs/gpu.md:
// the H200 ran 765-990 MHz of its 1980 under drained frames), so a drained
// measurement times the clock governor as much as the kernels. The default
// mode therefore keeps the GPU busy: frames are recorded back to back, many
// to one submission ("batch"), each pass in its own timestamp scope in every
// frame, and the queue is drained once per batch. The drained mode ("cold",
// one frame per submission, waited for) stays as an option and is labelled.
//
// Warm-up runs until the frame time is steady (two consecutive batches'
// median frame times within `steadyTolerance`, and the SM clock unchanged
// where it can be read), not for a fixed count; measurement stops when the
// 95% confidence interval of every median is narrow enough (`maxNoise`), or
// at `maxSeconds`, or after exactly `frames` frames when maxNoise is 0.
//
// Which clock is believed is decided once per measurement, before it starts
// (or given by the caller, so that repetitions of one configuration share
// it): GPU timestamps when they bracket the work, else the drained wall
// clock of each pass alone. Every measured batch is checked against its
// own wall time; a batch that fails is reported and left out, never pooled.
#pragma once

#include "measure/namespace.h"
#include "backend.h"
#include "measure/gpu_clocks.h"
#include "pipeline/pipeline.h"
#include "stats/stats.h"

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cavity::measure {

struct Series {
    std::string name;
    std::vector<double> ms;      // one sample per measured frame
    Stats stats;
};

enum class TimingMode { Batch, Drained };

// The fewest frames a hard time limit leaves: a median and its noise need some.
constexpr int kMinTimedFrames = 3;
const char* timingModeName(TimingMode m);   // "batch", "drained"

struct TimingOptions {
    TimingMode mode = TimingMode::Batch;
    int warmup = 5;                 // warm-up frames at least
    bool steadyWarmup = true;       // then on until steady (or warmupSeconds)
    double steadyTolerance = 0.01;  // consecutive batch medians within this share
    double warmupSeconds = 2.0;
    int frames = 50;                // measured frames at least; exactly this many when maxNoise is 0
    double maxNoise = 0.005;        // target half-width of the medians' 95% interval, relative; 0: fixed count
    double maxSeconds = 2.0;        // measurement time limit (with at least `frames` frames)
    // maxSeconds given by the user (--max-time): a limit even before `frames`
    // are measured (at least kMinTimedFrames), rather than a limit on the
    // noise search alone. `stop` then says "time" with fewer frames.
    bool hardTimeLimit = false;
    double batchMs = 25;            // GPU time per batch (batch mode); sets frames per submission
    int maxBatch = 256;
    std::optional<std::string> clock;   // "gpu-timestamp" or "wall": skip the decision (repetitions)
};

// The defaults for a device: hardware GPUs stop on noise after a steady
// warm-up; software renderers (whose noise is the host's load, and whose
// frames take tens of ms) run a fixed count with a fixed warm-up.
TimingOptions defaultTimingOptions(const gpu::DeviceInfo& device);

struct Timing {
    std::string clock;           // "gpu-timestamp" or "wall"
    // Why the wall clock was used, when it was; or, on timestamps, that the
    // warm decision overrode the cold probe or the configuration's first
    // repetition. Empty: timestamps, decided warm, nothing to say.
    std::string clockNote;
    TimingMode mode = TimingMode::Batch;   // as run: the wall clock always times passes drained
    int batchFrames = 1;         // frames per submission
    std::vector<Series> passes;  // in pass order, on `clock`
    Series frame;                // the whole frame, on `clock`
    // The AO pipeline: every pass but the G-buffer, per frame, on `clock`.
    // cavity_bench's time and `cavity run`'s summary are this series, so the
    // two formats name the same total the same way.
    Series pipeline;
    Series frameWall;            // wall time per frame (batch mode: the batch's wall time over its frames)
    Series frameGpu;             // sum of the pass timestamps of each frame
    // How the measurement went.
    int warmupFrames = 0;
    double warmupSeconds = 0;
    bool steadyChecked = false;  // warm-up ran on until steady (or its time limit)
    bool steady = false;         // ... and reached a steady frame time
    std::string stop;            // "frames", "noise" or "time"
    double noise = 0;            // achieved: largest relative half-width of a median's 95% interval
    double seconds = 0;          // measurement time
    int rejectedFrames = 0;      // frames of batches that failed the clock check (left out)
    std::string rejectedNote;    // the first such batch
    GpuClockSummary clocks;      // SM and memory clock over the measurement, where readable
};

// When the GPU timestamps are believed: they may not exceed the drained wall
// time (plus timer slop), and they must account for at least half of it
// unless the difference is within the fixed submission overhead.
// A warm check that fails is tried this many times more before the clock
// moves to the wall clock (decideWarm, timing.cpp).
constexpr int kClockRetries = 2;

struct ClockCheck {
    double maxOverWall = 1.05, slopMs = 0.02;
    double minFraction = 0.5, overheadMs = 0.3;
    // Test double of a timer that misreads while cold: the first this many
    // checks fail whatever they compare.
    mutable int distrustFirst = 0;
    // Test double of a timer that reads right once warm: after those, every
    // check passes whatever it compares (on a CPU renderer the checks pass or
    // fail by the host's load, which no test can rely on).
    bool trustRest = false;
    // Whether a cold probe's failure keeps the wall clock even when the warm
    // probe passes. Unset: on a software renderer, whose timestamps pass or
    // fail by the host's load (llvmpipe's GL ones miss deferred draws), yes;
    // on a GPU, no: the warm GPU decides.
    std::optional<bool> coldCounts;
    bool trusted(double gpuMs, double wallMs) const;
};

// Half-width of the distribution-free 95% confidence interval of the median
// (order statistics n/2 -+ 0.98 sqrt(n)), relative to the median; infinity
// below 8 samples.
double medianNoise(std::vector<double> samples);

// Measures `chains` (inputs rotated among them: frame f records chain
// f % size) on `gpu`. `clocks` may be null.
Result<Timing> measurePasses(gpu::Backend& gpu, std::span<PassChain* const> chains, const TimingOptions& options,
                       GpuClocks* clocks = nullptr, const ClockCheck& check = {});
Result<Timing> measurePasses(gpu::Backend& gpu, PassChain& chain, const TimingOptions& options,
                       GpuClocks* clocks = nullptr, const ClockCheck& check = {});

}  // namespace cavity::measure